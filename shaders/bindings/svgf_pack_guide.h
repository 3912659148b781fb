// svgf_pack_guide: this frame's edge-stopping guide (normal.xyz, depth), depth = −1 on background
// pixels (object id kNoObject), so the spatial filters fetch one texel per tap instead of three.
#define SVGF_GUIDE_BINDING_LIST(B)                          \
    B(SVGF_GUIDE, DEPTH, 0, DTEXEL, R32F, depth)            \
    B(SVGF_GUIDE, NORMAL, 1, NTEXEL, RGB32F, normal)        \
    B(SVGF_GUIDE, OBJECT, 2, OTEXEL, R32UI, object_id)     \
    B(SVGF_GUIDE, OUT, 3, WRITE, vec4, guide_out)
