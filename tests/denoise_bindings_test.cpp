// Binding lists (shaders/bindings/*.h): each pass's slots are 0 … count − 1, each once, and the
// host's texel-format tables follow the kinds (history planes switch to their 16-bit twin).
#include <catch2/catch.hpp>

#include <set>
#include <string>
#include <vector>

#include "denoise/vulkan/svgf_texel_formats.h"  // StageTexelFormats
#include "shaders/common/two_history_constants.glsl"

using namespace fovrt;

namespace {
struct Row {
    std::string name;
    int slot;
};
#define FOVRT_TEST_ROW(pass, name, slot, kind, format, variable) rows.push_back({#pass "_" #name, slot});
#define FOVRT_TEST_ROWS(LIST)          \
    [] {                               \
        std::vector<Row> rows;         \
        LIST(FOVRT_TEST_ROW)           \
        return rows;                   \
    }()

void CheckSlots(const std::vector<Row>& rows) {
    std::set<int> slots;
    for (const Row& r : rows) {
        INFO(r.name);
        CHECK(slots.insert(r.slot).second);  // no slot twice
    }
    CHECK(*slots.begin() == 0);
    CHECK(*slots.rbegin() == int(rows.size()) - 1);  // none skipped
}
}  // namespace

TEST_CASE("binding lists: slots 0..count-1, each once") {
    CheckSlots(FOVRT_TEST_ROWS(SVGF_REPROJECT_BINDING_LIST));
    CheckSlots(FOVRT_TEST_ROWS(SVGF_REPROJECT_PAIR_ALL_BINDING_LIST));
    CheckSlots(FOVRT_TEST_ROWS(TH_REPROJECT_BINDING_LIST));
    CheckSlots(FOVRT_TEST_ROWS(TH_REPROJECT_PAIR_ALL_BINDING_LIST));
    CheckSlots(FOVRT_TEST_ROWS(SVGF_GUIDE_BINDING_LIST));
    CheckSlots(FOVRT_TEST_ROWS(SVGF_CLASSIFY_BINDING_LIST));
    CheckSlots(FOVRT_TEST_ROWS(SVGF_MOMENTS_BINDING_LIST));
    CheckSlots(FOVRT_TEST_ROWS(SVGF_ATROUS_BINDING_LIST));
    CheckSlots(FOVRT_TEST_ROWS(SVGF_ATROUS_PAIR_ALL_BINDING_LIST));
    CheckSlots(FOVRT_TEST_ROWS(SVGF_MODULATE_BINDING_LIST));
    CheckSlots(FOVRT_TEST_ROWS(TH_GRADIENT_BINDING_LIST));
    CheckSlots(FOVRT_TEST_ROWS(TH_BLEND_BINDING_LIST));
    CheckSlots(FOVRT_TEST_ROWS(ASVGF_CLAIM_BINDING_LIST));
    CheckSlots(FOVRT_TEST_ROWS(ASVGF_GATHER_BINDING_LIST));
    CheckSlots(FOVRT_TEST_ROWS(ASVGF_SIGMA_BINDING_LIST));
    CheckSlots(FOVRT_TEST_ROWS(ASVGF_ATROUS_BINDING_LIST));
    CheckSlots(FOVRT_TEST_ROWS(ASVGF_ALPHA_BINDING_LIST));
    CheckSlots(FOVRT_TEST_ROWS(BANDWIDTH_BINDING_LIST));
    CheckSlots(FOVRT_TEST_ROWS(RAE_CONV_BINDING_LIST));
    CheckSlots(FOVRT_TEST_ROWS(RAE_POOL_BINDING_LIST));
    CHECK(SVGF_ATROUS_PAIR_BINDINGS == SVGF_ATROUS_BINDINGS + 3);
    // Both reprojection shaders bind the shared inputs at the same slots (ReprojectionInputs in
    // denoise/svgf_family_plan.cpp).
    CHECK(TH_REPROJECT_B_LIST == SVGF_REPROJECT_B_LIST);
    CHECK(TH_REPROJECT_B_COLOR_IN2 == SVGF_REPROJECT_B_COLOR_IN2);
    CHECK(SVGF_REPROJECT_PAIR_BINDINGS == 32);  // lavapipe: at most 32 storage buffers per stage
    CHECK(TH_REPROJECT_PAIR_BINDINGS == 41);
}

TEST_CASE("texel-format tables follow the binding kinds") {
    using S = StageShader;
    const Precision p32 = Precision::Fp32, p16 = Precision::Fp16;
    const auto fp32 = StageTexelFormats(S::FilterMoments, false, p32);
    const auto fp16 = StageTexelFormats(S::FilterMoments, false, p16);
    CHECK(fp32[SVGF_MOMENTS_B_ILLUM_IN] == VK_FORMAT_R32G32B32A32_SFLOAT);       // HTEXEL
    CHECK(fp16[SVGF_MOMENTS_B_ILLUM_IN] == VK_FORMAT_R16G16B16A16_SFLOAT);       // stored at the precision
    CHECK(fp16[SVGF_MOMENTS_B_GUIDE] == VK_FORMAT_R32G32B32A32_SFLOAT);          // TEXEL: 32-bit either way
    CHECK(fp32[SVGF_MOMENTS_B_MOMENTS] == VK_FORMAT_R32G32_SFLOAT);              // HTEXEL
    CHECK(fp16[SVGF_MOMENTS_B_MOMENTS] == VK_FORMAT_R16G16_SFLOAT);
    CHECK(fp16[SVGF_MOMENTS_B_LENGTH] == VK_FORMAT_R16_SFLOAT);
    CHECK(fp32[SVGF_MOMENTS_B_ILLUM_OUT] == VK_FORMAT_UNDEFINED);                // WRITE: storage
    CHECK(fp32[SVGF_MOMENTS_B_LIST] == VK_FORMAT_UNDEFINED);                     // LIST: storage
    // DTEXEL and OTEXEL: depth is R32F and ids R32UI in fp32; in fp16 both slots view the one
    // plane of depth + id codes as R32UI.
    CHECK(StageTexelFormats(S::PackGuide, false, p32)[SVGF_GUIDE_B_OBJECT] == VK_FORMAT_R32_UINT);
    CHECK(StageTexelFormats(S::PackGuide, false, p16)[SVGF_GUIDE_B_OBJECT] == VK_FORMAT_R32_UINT);
    CHECK(StageTexelFormats(S::PackGuide, false, p32)[SVGF_GUIDE_B_DEPTH] == VK_FORMAT_R32_SFLOAT);
    CHECK(StageTexelFormats(S::PackGuide, false, p16)[SVGF_GUIDE_B_DEPTH] == VK_FORMAT_R32_UINT);
    CHECK(StageTexelFormats(S::TwoHistoryReproject, true, p16)[TH_REPROJECT_B_PREV_DEPTH] == VK_FORMAT_R32_UINT);
    // NTEXEL: a normal is RGB32F in fp32 and an octahedral R16G16_SINT code in fp16.
    CHECK(StageTexelFormats(S::PackGuide, false, p32)[SVGF_GUIDE_B_NORMAL] == VK_FORMAT_R32G32B32_SFLOAT);
    CHECK(StageTexelFormats(S::PackGuide, false, p16)[SVGF_GUIDE_B_NORMAL] == VK_FORMAT_R16G16_SINT);
    CHECK(StageTexelFormats(S::SvgfReproject, false, p16)[SVGF_REPROJECT_B_PREV_NORMAL] == VK_FORMAT_R16G16_SINT);
    // A colour input (HTEXEL of RGB32F) is RGBA16F in fp16: RGB16F texel buffers are rarely supported.
    CHECK(StageTexelFormats(S::SvgfReproject, false, p16)[SVGF_REPROJECT_B_COLOR_IN] == VK_FORMAT_R16G16B16A16_SFLOAT);
    CHECK(StageTexelFormats(S::SvgfReproject, false, p32)[SVGF_REPROJECT_B_COLOR_IN] == VK_FORMAT_R32G32B32_SFLOAT);
    // HTEXEL3: an RGB history is a texel buffer in fp32 and storage in fp16.
    CHECK(StageTexelFormats(S::TwoHistoryBlend, false, p32)[TH_BLEND_B_S] == VK_FORMAT_R32G32B32_SFLOAT);
    CHECK(StageTexelFormats(S::TwoHistoryBlend, false, p16)[TH_BLEND_B_S] == VK_FORMAT_UNDEFINED);
    CHECK(StageTexelFormats(S::Atrous, true, p32)[SVGF_ATROUS_B_ILLUM_IN2] == VK_FORMAT_R32G32B32A32_SFLOAT);
    CHECK(StageTexelFormats(S::TwoHistoryReproject, true, p32)[TH_REPROJECT_B_PREV_IW2] == VK_FORMAT_R32G32B32_SFLOAT);
    CHECK(StageTexelFormats(S::TwoHistoryReproject, true, p16)[TH_REPROJECT_B_PREV_IW2] == VK_FORMAT_UNDEFINED);
    CHECK(StageTexelFormats(S::TwoHistoryReproject, true, p16)[TH_REPROJECT_B_PREV_M2] == VK_FORMAT_R16G16_SFLOAT);
    CHECK(StageTexelFormats(S::SvgfReproject, true, p16)[SVGF_REPROJECT_B_PREV_WEIGHT2] == VK_FORMAT_R16_SFLOAT);
    CHECK(StageTexelFormats(S::SvgfReproject, true, p32)[SVGF_REPROJECT_B_SAMPLE_COUNT] == VK_FORMAT_UNDEFINED);
    CHECK(StageTexelFormats(S::Atrous, true, p32)[SVGF_ATROUS_B_HIST_COLOR2] == VK_FORMAT_UNDEFINED);
}
