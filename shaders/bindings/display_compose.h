// display_compose: both eyes' linear RGB in one buffer, the left eye then the right
// (float[2·3·W·H], eye k's pixel i = y·W + x at 3·(k·W·H + i)) → the window's packed 8-bit pixels
// (uint[outW·outH], i = y·outW + x; byte order by DISPLAY_FLAG_BGRA). One buffer, so a pixel
// costs one fetch whichever eye it shows (lavapipe gathers from both sides of a select).
#define DISPLAY_COMPOSE_BINDING_LIST(B)              \
    B(DISPLAY_COMPOSE, EYES, 0, READ, float, eyes)   \
    B(DISPLAY_COMPOSE, OUT, 1, WRITE, uint, display_out)
