// rae_conv, rae_pool (denoise/vulkan/rae_vk.cpp): every tensor of a frame lives in one activation
// buffer (hfloat: float, or float16_t in the _fp16 variants) at the offsets of RaeTensorLayout
// (denoise/rae_weights.h), so one descriptor set serves every layer and concatenation, upsampling
// and the hidden state's A/B sides are addressing (push constants), not copies. Weights: fp32,
// each conv's [out][in][3][3] then its bias, in .raew order.
#define RAE_CONV_BINDING_LIST(B)                  \
    B(RAE_CONV, ACT, 0, RW, hfloat, act)          \
    B(RAE_CONV, WEIGHTS, 1, READ, float, weights)
#define RAE_POOL_BINDING_LIST(B)         \
    B(RAE_POOL, ACT, 0, RW, hfloat, act)

#define RAE_FLAG_LEAKY 1u       // leaky ReLU 0.1 after the conv (all but the output layer)
#define RAE_FLAG_UPSAMPLE_A 2u  // input a is at half resolution: 2×2 nearest upsample by addressing
#define RAE_OUT_PER_INVOCATION 4  // output channels one invocation accumulates (input loads shared)
#define RAE_PIXELS_PER_INVOCATION 8  // rae_conv: consecutive pixels of a row per invocation
#define RAE_WORKGROUP 8           // 8×8 invocations per workgroup
