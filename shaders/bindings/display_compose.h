// display_compose: both eyes' linear RGB (float[3·W·H] each, i = y·W + x) → the window's packed
// 8-bit pixels (uint[outW·outH], i = y·outW + x; byte order by DISPLAY_FLAG_BGRA).
#define DISPLAY_COMPOSE_BINDING_LIST(B)                 \
    B(DISPLAY_COMPOSE, LEFT, 0, READ, float, left_eye)  \
    B(DISPLAY_COMPOSE, RIGHT, 1, READ, float, right_eye) \
    B(DISPLAY_COMPOSE, OUT, 2, WRITE, uint, display_out)
