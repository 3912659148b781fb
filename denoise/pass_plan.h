// The pass plan of a denoiser variant: the ordered passes one frame runs and, for each, everything
// its readers need, built in one place from the variant row, the parameters and the size.
//   - The Vulkan host (denoise/vulkan/svgf_family_vk.h) records each pass's commands: pipelines
//     (shader variant + specialization constants), bindings (slot → plane and history side),
//     push-constant blocks, dispatch shapes (image, 2×2 à-trous blocks, strata, gradient
//     samples, or indirect over a pixel list), fills, copies and transfers.
//   - The C++ reference (denoise/reference/svgf_family_ref.h) runs each pass's ReferenceStage:
//     one function of denoise/reference/*_ref.h, on the planes the stage names.
//   - The memory plan is the union of the planes the commands name (denoise/planes.h sizes them),
//     the planes that live only within a frame sharing the slots of a transient pool
//     (denoise/transient_pool.h).
//   - The byte model of `fovrt bench` (denoise/bench/pass_bytes.h) is the sum of each pass's
//     uses, derived from its commands.
// The lavapipe-driven choices are properties of the commands, kept out of the maths: both
// channels in one dispatch ("_pair" variants), 2×2 à-trous blocks ("_step1" at step 1), the
// reprojection's 3×3 fallback as a second pass over a pixel list ("_box", indirect), modes as
// specialization constants (denoise/svgf.md).
//
// Byte-model convention: every plane a dispatch binds counts once per dispatch, whatever its
// gather footprint (5×5 à-trous, 7×7 moments, bilinear taps hit cache), so a pass's sum is its
// compulsory traffic: a lower bound on the bytes it moves.
#pragma once

#include <array>
#include <compare>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "denoise/denoiser.h"
#include "denoise/history_window.h"
#include "denoise/params.h"
#include "denoise/planes.h"
#include "denoise/stage_shaders.h"

namespace fovrt {

// Which part of a plane a use touches, resolved when the bytes are counted (PassBytesOptions).
enum class Coverage : uint8_t {
    EveryPixel,          // the whole plane (in a dispatch over a pixel list: the listed pixels)
    ListedPixels,        // the pixels on the spatial-variance list (svgf_filter_moments)
    FallbackPixels,      // the pixels whose bilinear reprojection taps all failed (none in the
                         // steady state)
    StratumGuidePixels,  // one pixel per 3×3 stratum (A-SVGF's gather of the stratum guide)
    ClaimedStrata,       // strata that received a gradient sample
    UploadedSamples,     // the uploaded share of the gradient-sample capacity (two per stratum)
};

enum class Access : uint8_t {
    Read,
    Write,
    ReadWrite,
    Unused,  // bound because the layout has the slot; a mode folds the access away
};

// When a pass or command runs, decided per frame by the host and the reference.
enum class When : uint8_t {
    Always,
    HasPrevious,      // the histories hold a previous frame (not after a reset or cut)
    NoPrevious,       // the first frame after a reset or cut
    GradientSamples,  // the frame carries A-SVGF gradient samples
};

// What a frame decides the Whens by.
struct FrameConditions {
    bool hasPrevious = false;
    bool gradientSamples = false;
};
bool Holds(When when, const FrameConditions& frame);

// ---- Vulkan commands ------------------------------------------------------------------------

struct Binding {
    int slot = 0;
    PlaneRef plane;
    Access access = Access::Read;
    Coverage coverage = Coverage::EveryPixel;
    double share = 1.0;  // the part of the covered plane one use moves (a gather of one sample
                         // of the two each stratum has room for: 0.5)
    double placeholderBytesPerPixel = 0.0;  // > 0: the shader loads this much per pixel whatever
                                            // is bound (a placeholder plane)
};

// Int specialization constants by constant_id (ids a shader does not declare are ignored).
struct Specialization {
    std::array<int32_t, 6> values{};  // ids 0..5 (shaders/shared_constants.h)
    uint8_t count = 0;
    // values[id] = value for each pair, −1 for the ids in between.
    static Specialization Of(std::initializer_list<std::pair<int, int32_t>> idValues);
    auto operator<=>(const Specialization&) const = default;
};

// One compiled pipeline: a shader variant (shaders/CMakeLists.txt builds "<stem>[_pair]
// [_step1|_box][_fp16]") with its specialization constants.
struct PipelineKey {
    StageShader shader = StageShader::PackGuide;
    bool pair = false;   // two illumination channels per dispatch
    bool step1 = false;  // svgf_atrous at step 1
    bool box = false;    // the reprojection's 3×3 fallback pass
    bool fp16 = false;   // 16-bit history storage
    Specialization spec;
    auto operator<=>(const PipelineKey&) const = default;
};
// "svgf_atrous_pair_step1_fp16": the name ShaderCode() knows it by.
std::string ShaderVariantName(const PipelineKey& key);
// Binding count of the variant's layout.
int BindingCount(const PipelineKey& key);

// Push-constant values the host sets per frame (the rest are fixed by the plan): whether there is
// a previous frame, the gradient samples uploaded, and the corner of the weighted history's
// window (denoise/history_window.h) this frame and the previous one.
enum class FrameValue : uint8_t {
    HasPrevious, GradientSampleCount, WindowOriginX, WindowOriginY, PrevWindowOriginX, PrevWindowOriginY
};

// A push-constant block (shaders/push_constants.h) filled when the plan is built.
struct PushBlock {
    std::array<uint32_t, 16> words{};
    uint32_t bytes = 0;
    std::vector<std::pair<uint32_t, FrameValue>> perFrame;  // (word, value) set per frame

    template <typename Block>
    static PushBlock Of(const Block& block) {
        static_assert(sizeof(Block) <= sizeof(words) && sizeof(Block) % 4 == 0);
        PushBlock p;
        std::memcpy(p.words.data(), &block, sizeof(Block));
        p.bytes = sizeof(Block);
        return p;
    }
};
// Marks push field `field` of struct `Block` as set per frame to `value`.
#define FOVRT_PUSH_PER_FRAME(push, Block, field, value) \
    (push).perFrame.push_back({uint32_t(offsetof(Block, field) / 4), value})
// Marks ivec2 push field `field` as the window origin of this frame (or the previous one).
#define FOVRT_PUSH_WINDOW_ORIGIN(push, Block, field)                              \
    (FOVRT_PUSH_PER_FRAME(push, Block, field, FrameValue::WindowOriginX),         \
     (push).perFrame.push_back({uint32_t(offsetof(Block, field) / 4 + 1), FrameValue::WindowOriginY}))
#define FOVRT_PUSH_PREV_WINDOW_ORIGIN(push, Block, field)                         \
    (FOVRT_PUSH_PER_FRAME(push, Block, field, FrameValue::PrevWindowOriginX),     \
     (push).perFrame.push_back({uint32_t(offsetof(Block, field) / 4 + 1), FrameValue::PrevWindowOriginY}))

enum class Grid : uint8_t {
    Pixels,           // one invocation per pixel
    AtrousBlocks,     // one invocation per 2×2 block at stride `step`
    Strata,           // one invocation per 3×3 stratum
    GradientSamples,  // one invocation per uploaded gradient sample (1-D)
    PixelList,        // indirect: one invocation per listed pixel (`listArgs` holds the groups)
};

struct DispatchCommand {
    PipelineKey pipeline;
    std::vector<Binding> bindings;
    PushBlock push;
    Grid grid = Grid::Pixels;
    int step = 1;                                   // AtrousBlocks
    PlaneId listArgs{};                             // PixelList
    Coverage listCoverage = Coverage::EveryPixel;   // PixelList: which pixels the list holds
};
struct FillCommand {
    PlaneRef plane;
    uint32_t value = 0;
};
struct CopyCommand {
    PlaneRef from, to;
};
// A FrameInputs plane (FrameSource of the plane's kind) through the staging ring into the device
// plane.
struct UploadCommand {
    PlaneRef to;
    Coverage coverage = Coverage::EveryPixel;
};
// A device plane through the staging ring to the host.
struct DownloadCommand {
    PlaneRef from;
};
// Every device plane to its ClearValue: histories dropped (Reset, cut, resize).
struct ClearCommand {};
// Earlier writes visible to later commands (and to indirect-argument reads).
struct BarrierCommand {};

struct Command {
    When when = When::Always;
    std::variant<DispatchCommand, FillCommand, CopyCommand, UploadCommand, DownloadCommand,
                 ClearCommand, BarrierCommand>
        op;
};

// ---- The reference's stages -----------------------------------------------------------------

// One channel's plane through a stage: illumination + variance `in` → `out`, and the colour
// history this stage writes (the reprojection without à-trous feedback, the feedback iteration).
struct StagePlane {
    Channel channel = Channel::None;
    PlaneId in, out;
    std::optional<PlaneRef> history;
};
// svgf_reproject (SvgfReprojectRef per channel) or two_history_reproject
// (TwoHistoryReprojectRef): `outputs` the illumination planes written (Illum0, WIllum0).
// A stage carries the modes its mechanisms set, as the shader receives them, so that the
// reference runs from the plan alone and never reads the variant's row.
struct ReprojectStage {
    bool twoHistory = false;  // two_history_reproject's layout
    // The shader's mode bits (FOVRT_SPEC_REPROJECT_FLAGS): TH_REPROJECT_FLAG_* with twoHistory,
    // else SVGF_REPROJECT_FLAG_* (shaders/shared_constants.h).
    uint32_t flags = 0;
    std::vector<StagePlane> outputs;
};
struct FilterMomentsStage {  // SvgfFilterMomentsRef per plane
    std::vector<StagePlane> planes;
};
struct AtrousStage {  // SvgfAtrousRef per plane
    int iteration = 0;
    std::vector<StagePlane> planes;
};
struct BlendStage {  // TwoHistoryBlendRef per plane: `out` blended in place with `in` (I_w)
    std::vector<StagePlane> planes;
    PlaneId q;
    bool clamp = false;           // the clamp mechanism's box in place of p
    std::optional<PlaneRef> choice;  // the hysteresis mechanism's held choice in place of p
};
struct ChoiceStage {};  // TwoHistoryChoiceRef: the hysteresis variants' held choice from the state
struct EmaGradientStage {  // TwoHistoryGradientRef: the filtered gradient and these → q
    std::vector<PlaneId> illumination;
};
struct StabilizeStage {  // TwoHistoryStabilizeRef per plane: `in` → `out`, its L_s history in `history`
    std::vector<StagePlane> planes;
    std::optional<PlaneId> q;  // stabilize-antilag: the change detector that drives the weight
};
struct ModulateStage {  // SvgfModulateRef
    std::vector<PlaneId> illumination;
};
struct AsvgfGradientStage {  // AsvgfScatterGradientsRef → `scattered`, AsvgfGradientAtrousRef per iteration
    PlaneId scattered;
    std::vector<StagePlane> iterations;
};
struct AsvgfAlphaStage {  // AsvgfAlphaRef: α and λ from the reconstructed gradient
    PlaneId reconstructed;
    bool antilag = false;  // the anti-lag mechanism: λ also shortens the history
};
using ReferenceStage =
    std::variant<std::monostate, ReprojectStage, FilterMomentsStage, AtrousStage, BlendStage,
                 EmaGradientStage, ModulateStage, AsvgfGradientStage, AsvgfAlphaStage, StabilizeStage,
                 ChoiceStage>;

// ---- Passes ---------------------------------------------------------------------------------

// One plane use of the byte model.
struct PlaneUse {
    std::string plane;  // printed name without the history side
    Access access = Access::Read;  // Read or Write
    double times = 1.0;  // whole-plane transfers: 2 for an upload (staging read + device write)
    Coverage coverage = Coverage::EveryPixel;
    double planeBytesPerPixel = 0.0;  // bytes of the plane (one history side) per image pixel
    double fixedBytesPerPixel = 0.0;  // > 0: a placeholder binding's load, instead of the plane's
};

struct PlannedPass {
    std::string name;  // the GPU timer: "reproject", "atrous0", …; empty: recorded untimed
    When when = When::Always;
    // The C++ reference's timer ("" when it runs nothing here): consecutive passes with one
    // timer are timed as one (the two-history family's reference reports "asvgf_gradient" and
    // "atrous_blend" over several GPU passes).
    std::string referenceTimer;
    ReferenceStage stage;
    std::vector<Command> commands;
    std::vector<PlaneUse> uses;  // the byte model (SVGF family: derived from the commands)
};

// Where one plane of the plan lives (SVGF family).
struct PlanePlacement {
    BufferKey key;
    size_t bytes = 0;             // the plane's own size (a pool slot may be larger)
    size_t allocation = 0;        // its buffer in DenoiserPlan::buffers
    bool readAfterFrame = false;  // the host reads it after the frame (downloads, debug views)
};

struct DenoiserPlan {
    // The memory plan (PlanDenoiserMemory): every allocation, the permanent buffers and then the
    // transient pool's slots (denoise/transient_pool.h).
    std::vector<BufferPlan> buffers;
    std::vector<PlanePlacement> planes;  // every plane the commands name (SVGF family; RAE: empty)
    std::vector<PlannedPass> passes;     // recording order
};

// The plan of the named variant (DenoiserVariants(), without a demodulation suffix) at W×H for
// one eye. fovrt::Error for an unknown name or size.
DenoiserPlan BuildDenoiserPlan(std::string_view variant, const DenoiserParams& params, int width,
                               int height);

// The fraction of the image the variant's weighted history keeps (denoise.two_history.window for
// the variants with one, else 1), and its window this frame: what the host's and the reference's
// frames index the WINDOW_STORED planes by (denoise/history_window.h).
float WeightedWindowFraction(const DenoiserVariant& variant, const DenoiserParams& params);
HistoryWindow FrameWeightedWindow(const DenoiserVariant& variant, const DenoiserParams& params,
                                  const FrameInputs& frame);

// The plane a debug view reads in a variant's plan (HistoryLength, HistorySamples, Alpha,
// Lambda, Q); nullopt for views computed from several planes (P) or not offered.
std::optional<PlaneRef> DebugViewPlane(const DenoiserVariant& variant, const DenoiserParams& params,
                                       DebugViewId view);

}  // namespace fovrt
