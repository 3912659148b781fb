// The transient pool of an SVGF-family plan (NRD's transient pool, Falcor's render-graph aliasing):
// which planes hold a value only within a frame and when, read from the plan's commands, and their
// placement in shared allocations (slots) so that planes whose lifetimes do not overlap share
// memory. Histories, staging, fixed-size planes (counters, dispatch arguments) and scratch that
// carries a value from one frame to the next (written only under a condition: A-SVGF's α and λ
// hold the reset's 1 until a frame with a previous one) keep buffers of their own.
//
// Time within a frame is counted in epochs: the spans between the barriers every frame records.
// Commands of one epoch may run at once, so a plane is live in every epoch from that of its first
// write to that of its last use, both included.
#pragma once

#include <map>
#include <string>

#include "denoise/pass_plan.h"

namespace fovrt {

struct PlaneLifetime {
    // Every frame writes the plane whole (or appends the list it is) before anything reads it,
    // so what it held before the frame is never used.
    bool transient = false;
    int first = 0, last = 0;  // epochs of the first write and the last use
    bool Overlaps(const PlaneLifetime& o) const { return first <= o.last && o.first <= last; }
};

// The lifetime of every plane of `plan.planes` (a plane the host reads after the frame lives to
// the frame's end).
std::map<BufferKey, PlaneLifetime> PlaneLifetimes(const DenoiserPlan& plan);

// Fills plan.buffers and each plane's allocation from plan.planes (keys, sizes) and the commands:
// a buffer per permanent plane, in plane-table order, then the pool's slots; each transient plane
// goes, in order of first write, to the free slot it grows least.
void PlaceInTransientPool(DenoiserPlan& plan);

// Whether a plane still holds this frame's value once the frame ends: false when a plane written
// later shares its slot (read-backs of such a plane would read the later one).
bool HeldAfterFrame(const DenoiserPlan& plan, const BufferKey& key);

// The most bytes of transient planes live in one epoch: the floor of any pool for the plan.
size_t PeakLiveTransientBytes(const DenoiserPlan& plan);

// The validator: "" when no allocation holds a permanent plane beside another or two planes live
// in one epoch; else one line naming the first such pair.
std::string AliasingConflict(const DenoiserPlan& plan);

}  // namespace fovrt
