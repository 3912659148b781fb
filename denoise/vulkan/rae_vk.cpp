#include "denoise/vulkan/rae_vk.h"

#include <chrono>
#include <cstring>

#include <glm/gtc/packing.hpp>

#include "core/cpu_time.h"
#include "core/error.h"
#include "denoise/reference/rae_features.h"
#include "denoise/reference/rae_net.h"
#include "shaders/push_constants.h"
#include "shaders/shared_constants.h"
#include "vk/transfer_ring.h"

namespace fovrt {
namespace {


uint32_t Groups(int n, int per) { return uint32_t((n + per - 1) / per); }

}  // namespace

RaeVulkanDenoiser::RaeVulkanDenoiser(std::string name, std::shared_ptr<VulkanContext> context,
                                     const DenoiserParams& params)
    : name_(std::move(name)), context_(std::move(context)), weights_(SharedRaeWeights(params)),
      params_(params), fp16_(params.precision == Precision::Fp16), slot_(*context_), timestamps_(*context_, 8) {
    if (fp16_ && !context_->supports16BitStorage())
        Fail("rae: denoise.precision = fp16 needs 16-bit storage, which {} lacks", context_->deviceName());
    // Weights: each conv's [out][in][3][3], then its bias.
    std::vector<float> packed;
    for (const RaeConv& c : weights_->convs) {
        weightOffsets_.push_back(uint32_t(packed.size()));
        packed.insert(packed.end(), c.weight.begin(), c.weight.end());
        biasOffsets_.push_back(uint32_t(packed.size()));
        packed.insert(packed.end(), c.bias.begin(), c.bias.end());
    }
    weightBuffer_ = context_->allocator().CreateBuffer("rae.weights", packed.size() * 4);
    Buffer upload = context_->allocator().CreateBuffer("rae.weights.staging", packed.size() * 4, MemoryUsage::Staging);
    CommandRecorder rec(*context_);
    rec.Upload(packed.data(), packed.size() * 4, upload, 0, weightBuffer_);
    rec.Barrier();
    rec.Submit();
    const std::string suffix = fp16_ ? "_fp16" : "";
    conv_ = ComputePipeline(*context_, "rae_conv" + suffix, RAE_CONV_BINDINGS, sizeof(RaeConvPush), 1);
    pool_ = ComputePipeline(*context_, "rae_pool" + suffix, RAE_POOL_BINDINGS, sizeof(RaePoolPush), 1);
}

RaeVulkanDenoiser::~RaeVulkanDenoiser() = default;

void RaeVulkanDenoiser::Allocate(int pw, int ph) {
    if (pw == paddedWidth_ && ph == paddedHeight_) return;
    paddedWidth_ = pw;
    paddedHeight_ = ph;
    layout_ = RaeTensorLayout(*weights_, pw, ph);
    size_t floats = 0;
    for (const RaeTensorSlot& s : layout_) floats = std::max(floats, s.offset + s.Floats());
    const size_t element = fp16_ ? 2 : 4;
    conv_.ResetSets();
    pool_.ResetSets();
    activations_ = context_->allocator().CreateBuffer("rae.activations", floats * element);
    staging_ = context_->allocator().CreateBuffer("rae.staging", RaeStagingBytes(*weights_, pw, ph, params_),
                                                  MemoryUsage::Staging);
    const Buffer* convBuffers[RAE_CONV_BINDINGS] = {};
    convBuffers[RAE_CONV_B_ACT] = &activations_;
    convBuffers[RAE_CONV_B_WEIGHTS] = &weightBuffer_;
    convSet_ = conv_.MakeSet(convBuffers);
    const Buffer* poolBuffers[RAE_POOL_BINDINGS] = {&activations_};
    poolSet_ = pool_.MakeSet(poolBuffers);
    needsClear_ = true;
}

std::string RaeVulkanDenoiser::Hidden(int level, bool written) const {
    const bool a = written ? parity_ == 0 : parity_ == 1;
    return "rae.hidden" + std::to_string(level) + (a ? ".A" : ".B");
}

void RaeVulkanDenoiser::Conv(CommandRecorder& rec, int conv, const RaeTensorSlot& a, const RaeTensorSlot* b,
                             bool upsampleA, const RaeTensorSlot& dst, bool leaky) {
    const RaeConv& c = weights_->convs[size_t(conv)];
    const int tilesX = int(Groups(dst.width, RAE_WORKGROUP * RAE_PIXELS_PER_INVOCATION));
    const int outGroups = int(Groups(c.out, RAE_OUT_PER_INVOCATION));
    const RaeConvPush push{ivec2(dst.width, dst.height),
                           a.channels,
                           b ? b->channels : 0,
                           c.out,
                           uint32_t(a.offset),
                           uint32_t(b ? b->offset : 0),
                           uint32_t(dst.offset),
                           weightOffsets_[size_t(conv)],
                           biasOffsets_[size_t(conv)],
                           (leaky ? RAE_FLAG_LEAKY : 0u) | (upsampleA ? RAE_FLAG_UPSAMPLE_A : 0u),
                           tilesX};
    rec.Dispatch(conv_, convSet_, &push, sizeof(push),
                 uvec2(uint32_t(tilesX * outGroups), Groups(dst.height, RAE_WORKGROUP)));
    rec.BufferBarrier(activations_);
}

void RaeVulkanDenoiser::Pool(CommandRecorder& rec, const RaeTensorSlot& src, const RaeTensorSlot& dst) {
    const int tilesX = int(Groups(dst.width, RAE_WORKGROUP));
    const RaePoolPush push{ivec2(dst.width, dst.height), dst.channels, uint32_t(src.offset), uint32_t(dst.offset),
                           tilesX};
    rec.Dispatch(pool_, poolSet_, &push, sizeof(push),
                 uvec2(uint32_t(tilesX * dst.channels), Groups(dst.height, RAE_WORKGROUP)));
    rec.BufferBarrier(activations_);
}

void RaeVulkanDenoiser::RecordNetwork(CommandRecorder& rec) {
    const int L = weights_->Levels();
    const RaeConvOrder order{L};
    rec.BeginPass("rae_encoder");
    const RaeTensorSlot* input = &Slot("rae.input");
    for (int l = 0; l <= L; ++l) {
        const std::string p = l < L ? "rae.enc" + std::to_string(l) : "rae.bottleneck";
        const RaeTensorSlot &x = Slot(p + ".x"), &a = Slot(p + ".a"), &t = Slot(p + ".t");
        const RaeTensorSlot& h = Slot(Hidden(l, true));
        Conv(rec, l < L ? order.Encoder(l) : order.Bottleneck(), *input, nullptr, false, x, true);
        Conv(rec, order.Recurrent(l, 0), x, nullptr, false, a, true);
        Conv(rec, order.Recurrent(l, 1), a, &Slot(Hidden(l, false)), false, t, true);
        Conv(rec, order.Recurrent(l, 2), t, nullptr, false, h, true);
        if (l < L) {
            Pool(rec, h, Slot(p + ".pool"));
            input = &Slot(p + ".pool");
        }
    }
    rec.EndPass();
    rec.BeginPass("rae_decoder");
    const RaeTensorSlot* below = &Slot(Hidden(L, true));
    for (int l = L - 1; l >= 0; --l) {
        const std::string p = "rae.dec" + std::to_string(l);
        Conv(rec, order.Decoder(l, 0), *below, &Slot(Hidden(l, true)), true, Slot(p + ".a"), true);
        Conv(rec, order.Decoder(l, 1), Slot(p + ".a"), nullptr, false, Slot(p + ".b"), true);
        below = &Slot(p + ".b");
    }
    Conv(rec, order.Output(), *below, nullptr, false, Slot("rae.output"), false);
    rec.EndPass();
}

void RaeVulkanDenoiser::Forward(const Tensor& input, Tensor& out) {
    if (input.c != weights_->inChannels) Fail("rae: input has {} channels, the network {}", input.c, weights_->inChannels);
    Allocate(input.w, input.h);
    const RaeTensorSlot& in = Slot("rae.input");
    const RaeTensorSlot& o = Slot("rae.output");
    const size_t element = fp16_ ? 2 : 4;
    CommandRecorder rec(*context_, slot_, &timestamps_);
    TransferRing transfers(rec, staging_);
    rec.BeginPass("upload");
    if (needsClear_) {  // a reset: the previous hidden side reads zeros
        rec.Fill(activations_, 0u);
        rec.Barrier();
        needsClear_ = false;
    }
    FOVRT_CHECK(in.offset == 0);  // the upload fills activations_ from its start
    if (fp16_) {
        half_.resize(input.data.size());  // the ring copies it at once: free again after Upload
        for (size_t i = 0; i < half_.size(); ++i) half_[i] = glm::packHalf1x16(input.data[i]);
        transfers.Upload(half_.data(), half_.size() * 2, activations_);
    } else {
        transfers.Upload(input.data.data(), input.Bytes(), activations_);
    }
    rec.Barrier();
    rec.EndPass();
    RecordNetwork(rec);
    out = Tensor(3, o.height, o.width);
    half_.resize(fp16_ ? out.data.size() : 0);
    rec.BeginPass("download");
    if (fp16_)
        transfers.Download(activations_, half_.size() * 2, half_.data(), o.offset * element);
    else
        transfers.Download(activations_, out.Bytes(), out.data.data(), o.offset * element);
    rec.EndPass();
    transfers.Submit();
    timings_.clear();
    if (timestamps_.enabled())
        for (const auto& [pass, ms] : timestamps_.Results()) timings_.push_back({pass, ms});
    for (size_t i = 0; i < half_.size(); ++i) out.data[i] = glm::unpackHalf1x16(half_[i]);
    parity_ ^= 1;
}

void RaeVulkanDenoiser::ReadTensor(const std::string& name, Tensor& out) {
    std::string slotName = name;
    if (name.rfind("rae.hidden", 0) == 0 && name.rfind('.') == 3)  // "rae.hiddenN": the side written last
        slotName = name + ((parity_ ^ 1) == 0 ? ".A" : ".B");
    const RaeTensorSlot& s = Slot(slotName);
    const size_t element = fp16_ ? 2 : 4;
    Buffer tmp = context_->allocator().CreateBuffer("rae.readback", s.Floats() * element, MemoryUsage::Staging);
    CommandRecorder rec(*context_);
    const VkBufferCopy region{s.offset * element, 0, s.Floats() * element};
    vkCmdCopyBuffer(rec.commandBuffer(), activations_.handle(), tmp.handle(), 1, &region);
    rec.Barrier();
    rec.Submit();
    out = Tensor(s.channels, s.height, s.width);
    if (fp16_) {
        const uint16_t* h = static_cast<const uint16_t*>(tmp.mapped());
        for (size_t i = 0; i < out.data.size(); ++i) out.data[i] = glm::unpackHalf1x16(h[i]);
    } else {
        std::memcpy(out.data.data(), tmp.mapped(), out.Bytes());
    }
}

void RaeVulkanDenoiser::Denoise(const FrameInputs& inputs, Plane<vec3>& output) {
    auto start = std::chrono::steady_clock::now();
    if (inputs.cameraCut) needsClear_ = true;
    Tensor features, input, y;
    RaeFeatures(inputs, features);
    const vec3 gains = params_.rae.balance ? RaeBalanceGains(features) : vec3(1.0f);
    RaeNetworkInput(features, *weights_, input, gains);
    const double featureMs = MsSince(start);
    Forward(input, y);
    start = std::chrono::steady_clock::now();
    RaeRemodulate(inputs, y, weights_->gamma, output, gains);
    timings_.insert(timings_.begin(), {"rae_features", featureMs});
    timings_.push_back({"rae_remodulate", MsSince(start)});
}

}  // namespace fovrt
