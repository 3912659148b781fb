// SerializeScene: one canonical byte stream of everything in a loaded Scene that can change its
// rendered image (geometry, materials, textures, lights, camera path, animation, background).
// Used by nothing but hashing: the reference cache keys its entries on a hash of this stream
// (pipeline/reference_cache.h), so a field missing here would let a changed scene hit a stale entry.
// Every field of every scene struct is bound by name in scene_serialize.cpp, so adding a field
// stops that file compiling until it is either written or named there as not changing the image.
#pragma once

#include <cstddef>
#include <functional>

#include "scene/scene.h"

namespace fovrt {

// Receives the stream in order, in chunks of any size (concatenating them gives the stream).
using ByteSink = std::function<void(const void* data, size_t size)>;

// Writes the stream: fixed-width little-endian values, counts before every list, a version tag
// first. Names and source paths are left out (they never change an image).
void SerializeScene(const Scene& scene, const ByteSink& sink);

}  // namespace fovrt
