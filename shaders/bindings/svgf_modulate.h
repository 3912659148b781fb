// svgf_modulate: albedo · (filtered direct + filtered indirect) + emission → output, `albedo`
// being the frame's modulation factor (albedo or F_β, buffer input.modulation) (combined:
// ILLUM0 holds both and ILLUM1 is not read; specialization constant FOVRT_SPEC_MODULATE_COMBINED).
#define SVGF_MODULATE_BINDING_LIST(B)                        \
    B(SVGF_MODULATE, ILLUM0, 0, HTEXEL, RGBA32F, illum0)     \
    B(SVGF_MODULATE, ILLUM1, 1, HTEXEL, RGBA32F, illum1)     \
    B(SVGF_MODULATE, ALBEDO, 2, HTEXEL, RGB32F, albedo)      \
    B(SVGF_MODULATE, EMISSION, 3, HTEXEL, RGB32F, emission)  \
    B(SVGF_MODULATE, OUT, 4, WRITE, float, color_out)
