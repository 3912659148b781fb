// A compacted list of pixel indices and the indirect-dispatch arguments that run a pass over it:
// args = (groups x, groups y, 1, count), zeroed by the host before the pass that appends. Why:
// lavapipe executes every branch under a lane mask, so work that only a few pixels need (the
// spatial variance estimate, the reprojection's 3×3 fallback) costs the whole image unless those
// pixels are listed and a second dispatch runs over the list only.
// The consumer runs FOVRT_SPATIAL_LIST_GROUP invocations per workgroup on a 2-D grid of groups
// (x ≤ FOVRT_SPATIAL_LIST_MAX_GROUPS, y rows of those: lists beyond 4.19 M pixels, e.g. 2064×2208
// per eye) and handles one entry per invocation: `if (pixel_list_entry(k)) work(pixel_list_at(k));`.
// Not a grid-stride loop: lavapipe runs a loop body once more, fully masked, before it sees that no
// lane continues, so a loop each lane runs once costs its body twice (measured, denoise/svgf.md).
// The including shader defines the bindings first:
//   #define PIXEL_LIST_B_ARGS <binding>   uint[4]
//   #define PIXEL_LIST_B_LIST <binding>   uint[N]
#ifndef FOVRT_PIXEL_LIST_GLSL
#define FOVRT_PIXEL_LIST_GLSL
#include "shared_constants.h"

layout(std430, binding = PIXEL_LIST_B_ARGS) buffer PixelListArgs { uint list_args[4]; };
layout(std430, binding = PIXEL_LIST_B_LIST) buffer PixelList { uint list_pixels[]; };

// Appends pixel i; the entry that opens a workgroup grows the group grid to cover it.
void pixel_list_append(int i) {
    uint k = atomicAdd(list_args[3], 1u);
    list_pixels[k] = uint(i);
    if (k % FOVRT_SPATIAL_LIST_GROUP == 0u) {
        uint group = k / FOVRT_SPATIAL_LIST_GROUP;
        atomicMax(list_args[0], min(group + 1u, FOVRT_SPATIAL_LIST_MAX_GROUPS));
        atomicMax(list_args[1], group / FOVRT_SPATIAL_LIST_MAX_GROUPS + 1u);
        if (k == 0u) list_args[2] = 1u;
    }
}

// This invocation's list position k, and whether it holds an entry.
bool pixel_list_entry(out uint k) {
    uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    k = group * FOVRT_SPATIAL_LIST_GROUP + gl_LocalInvocationID.x;
    return k < list_args[3];
}
int pixel_list_at(uint k) { return int(list_pixels[k]); }

#endif
