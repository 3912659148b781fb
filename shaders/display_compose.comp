#version 460
#extension GL_GOOGLE_include_directive : require
// display_compose — the live preview's last step (SPEC §11 "tonemap + sRGB encode → present"):
// both eyes, letterboxed into the window, through the display transform, with the gaze marker,
// fovea outline and (with a modelled tracker) the true gaze's marker on top, as packed 8-bit pixels a vkCmdCopyBufferToImage puts into the swapchain
// image unchanged (copies do not convert, so the bytes are sRGB-encoded for UNORM and SRGB
// swapchain formats alike).
// Reads:  both eyes' linear RGB (float[2·3·W·H], left then right); push constants (viewports,
//         gaze and fovea radius in fixed-point output pixels, exposure scale, flags).
// Writes: uint[outW·outH], one pixel per invocation: bytes R,G,B,A or B,G,R,A (DISPLAY_FLAG_BGRA).
// Sampling is nearest-neighbour: an output pixel shows the eye pixel that holds its centre (a
// preview; no filtering, so what is shown is what was rendered). The C++ reference is
// ComposeDisplayReference (src/display/display_compose.cpp).
// Speed (lavapipe, 2 cores, 1280×720 from 640×720 eyes, `live_display_pass_test "[.bench]"`):
// 8.4 ms; 11.0 ms with an exact integer division per pixel and a buffer per eye (a select
// between two fetches gathers from both).
#include "shared_constants.h"
#include "push_constants.h"
#include "common/packing.glsl"
#include "common/display_constants.glsl"
#include "common/display_transform.glsl"

layout(local_size_x = FOVRT_WORKGROUP_X, local_size_y = FOVRT_WORKGROUP_Y) in;

FOVRT_DECLARE_BINDINGS(DISPLAY_COMPOSE_BINDING_LIST)  // shaders/bindings/display_compose.h

FOVRT_PUSH_CONSTANTS(FOVRT_PUSH_DISPLAY_COMPOSE);  // shaders/push_constants.h

bool inside(ivec2 p, ivec2 origin) { return all(greaterThanEqual(p, origin)) && all(lessThan(p, origin + pc.extent)); }

// Display transform of one pixel → 0xRRGGBB.
uint display_rgb(vec3 hdr) {
    bool reinhard = (pc.flags & DISPLAY_FLAG_REINHARD) != 0u;
    return (fovrt_display_byte(hdr.r, pc.scale, reinhard) << 16) |
           (fovrt_display_byte(hdr.g, pc.scale, reinhard) << 8) | fovrt_display_byte(hdr.b, pc.scale, reinhard);
}

// True gaze × over gaze cross over fovea circle over the image. Distances in subpixels from p's
// centre.
uint overlay(ivec2 p, ivec2 gaze, int radius, bool showTrue, ivec2 trueGaze, uint under) {
    const int w = FOVRT_DISPLAY_LINE_HALF_WIDTH;
    const int arm = FOVRT_DISPLAY_MARKER_ARM;
    if (showTrue) {
        ivec2 t = abs(p * FOVRT_DISPLAY_SUBPIXELS + FOVRT_DISPLAY_SUBPIXELS / 2 - trueGaze);
        if (abs(t.x - t.y) <= FOVRT_DISPLAY_DIAGONAL_HALF_WIDTH && max(t.x, t.y) <= arm) return FOVRT_DISPLAY_TRUE_GAZE_RGB;
    }
    ivec2 a = abs(p * FOVRT_DISPLAY_SUBPIXELS + FOVRT_DISPLAY_SUBPIXELS / 2 - gaze);
    if ((a.x <= w && a.y <= arm) || (a.y <= w && a.x <= arm)) return FOVRT_DISPLAY_GAZE_RGB;
    if (radius > 0) {
        int hi = radius + w;
        int lo = max(radius - w, 0);
        if (a.x <= hi && a.y <= hi) {
            uint d2 = uint(a.x * a.x) + uint(a.y * a.y);
            if (d2 >= uint(lo * lo) && d2 <= uint(hi * hi)) return FOVRT_DISPLAY_FOVEA_RGB;
        }
    }
    return under;
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.out_size))) return;
    // The slot first, then one fetch, one transform and one overlay test: lavapipe runs both sides
    // of a divergent branch, so a transform per slot would cost twice.
    bool sideBySide = (pc.flags & DISPLAY_FLAG_SIDE_BY_SIDE) != 0u;
    int slot = inside(p, pc.origin0) ? 0 : sideBySide && inside(p, pc.origin1) ? 1 : -1;
    uint rgb = FOVRT_DISPLAY_BACKGROUND_RGB;
    if (slot >= 0) {
        bool first = slot == 0;
        // The eye pixel under p's centre: (p − origin + ½) · step, one correctly rounded multiply
        // per axis, exactly as the reference computes it.
        ivec2 e = min(ivec2((vec2(p - (first ? pc.origin0 : pc.origin1)) + 0.5) * vec2(pc.step_x, pc.step_y)),
                      pc.eye_size - 1);
        bool right = !first || (pc.flags & DISPLAY_FLAG_SLOT0_RIGHT) != 0u;
        int i = (right ? pc.eye_size.x * pc.eye_size.y : 0) + e.y * pc.eye_size.x + e.x;
        rgb = display_rgb(LOAD3(eyes, i));
        if ((pc.flags & (first ? DISPLAY_FLAG_MARK0 : DISPLAY_FLAG_MARK1)) != 0u)
            rgb = overlay(p, first ? pc.gaze0 : pc.gaze1, first ? pc.radius0 : pc.radius1,
                          (pc.flags & (first ? DISPLAY_FLAG_TRUE0 : DISPLAY_FLAG_TRUE1)) != 0u,
                          first ? pc.true_gaze0 : pc.true_gaze1, rgb);
    }
    // Little-endian words: 0xAARRGGBB is B,G,R,A in memory; R,G,B,A swaps the outer bytes.
    uint bgra = 0xFF000000u | rgb;
    uint rgba = 0xFF000000u | ((rgb & 0xFFu) << 16) | (rgb & 0xFF00u) | ((rgb >> 16) & 0xFFu);
    display_out[p.y * pc.out_size.x + p.x] = (pc.flags & DISPLAY_FLAG_BGRA) != 0u ? bgra : rgba;
}
