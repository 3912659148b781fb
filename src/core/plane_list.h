// Plane lists: a struct's per-pixel planes declared once, as one X-macro row per plane
//   X(member, element type, neutral value, EXR channels, doc)
// from which its fields, allocation, byte count, names and file layers all expand (FrameInputs,
// the renderer's VisibilityBuffer). A struct with such a list defines VisitPlanes(f), calling
// f(const PlaneSpec&, Plane<T>&) per plane in list order; the helpers below read nothing else.
#pragma once

#include <algorithm>

#include <cstddef>
#include <string>
#include <vector>

#include "image.h"

namespace fovrt {

// What a plane list says about one plane besides its type and neutral value.
struct PlaneSpec {
    const char* name;      // the member's name; also its EXR layer name
    const char* channels;  // EXR channel names, one letter per component ("RGB"); "" = one unnamed
    const char* doc;       // meaning and units
};

// One plane as bytes, for code that moves planes without knowing their types (GPU uploads,
// memory tables).
struct PlaneBytes {
    const char* name;
    const void* data;
    size_t elementSize;  // bytes per pixel
    size_t bytes;        // elementSize * width * height
};

// Row expanders for a plane list X-macro.
#define FOVRT_PLANE_MEMBER(member, Type, neutral, channels, doc) Plane<Type> member;
#define FOVRT_PLANE_RESIZE(member, Type, neutral, channels, doc) \
    member.Resize(width, height, neutral);
#define FOVRT_PLANE_RESIZE_FOR_OVERWRITE(member, Type, neutral, channels, doc) \
    member.ResizeForOverwrite(width, height, neutral);
// Sets rows y0..y1-1, columns x0..x1-1 of the plane to its neutral value.
#define FOVRT_PLANE_SET_NEUTRAL(member, Type, neutral, channels, doc) \
    for (int y = y0; y < y1; ++y) std::fill_n(&member(x0, y), x1 - x0, neutral);
#define FOVRT_PLANE_VISIT(member, Type, neutral, channels, doc) \
    f(PlaneSpec{#member, channels, doc}, member);
#define FOVRT_PLANE_NAME(member, Type, neutral, channels, doc) #member,

// f(PlaneBytes) for every plane of `planes`, in list order.
template <typename Planes, typename F>
void ForEachPlaneBytes(const Planes& planes, F&& f) {
    planes.VisitPlanes([&](const PlaneSpec& spec, const auto& plane) {
        f(PlaneBytes{spec.name, plane.data(), sizeof(*plane.data()), plane.bytes()});
    });
}

// Bytes held by every plane of `planes`.
template <typename Planes>
size_t TotalPlaneBytes(const Planes& planes) {
    size_t bytes = 0;
    ForEachPlaneBytes(planes, [&](const PlaneBytes& p) { bytes += p.bytes; });
    return bytes;
}

}  // namespace fovrt
