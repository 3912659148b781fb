// Swapchains: VkImages on the application's VkDevice (3 per swapchain, 1 when static), with the
// usage the application asked for plus COLOR_ATTACHMENT (the layout they live in needs it) and
// TRANSFER_SRC (the runtime's read-back). Each image is moved to COLOR_ATTACHMENT_OPTIMAL at its
// first acquire rather than at creation: the OpenXR spec lets a runtime touch the application's
// queue only in xrBeginFrame, xrEndFrame and xrAcquire/ReleaseSwapchainImage.
#include <algorithm>
#include <memory>

#include "runtime.h"

namespace fovrt::xrrt {

namespace {

// Preferred first, as real runtimes list them (sRGB for rasterised output, then the formats a
// compute shader can write).
constexpr VkFormat kFormats[] = {VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_B8G8R8A8_SRGB,
                                 VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_B8G8R8A8_UNORM,
                                 VK_FORMAT_R16G16B16A16_SFLOAT};
constexpr VkImageUsageFlags kRuntimeUsage =
    VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;

std::vector<VkFormat> SupportedFormats(VkPhysicalDevice device) {
    std::vector<VkFormat> list;
    constexpr VkFormatFeatureFlags kNeeded =
        VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
    for (VkFormat f : kFormats) {
        VkFormatProperties p{};
        vkGetPhysicalDeviceFormatProperties(device, f, &p);
        if ((p.optimalTilingFeatures & kNeeded) == kNeeded) list.push_back(f);
    }
    return list;
}

XrResult XRAPI_CALL EnumerateSwapchainFormats(XrSession handle, uint32_t capacity,
                                              uint32_t* count, int64_t* formats) {
    return OnRunningSession(handle, [&](Session* s) -> XrResult {
        std::vector<VkFormat> list = SupportedFormats(s->physicalDevice);
        return TwoCall(capacity, count, formats, uint32_t(list.size()),
                       [&](int64_t& f, uint32_t i) { f = list[i]; });
    });
}

bool MemoryType(VkPhysicalDevice device, uint32_t bits, VkMemoryPropertyFlags wanted,
                uint32_t* index) {
    VkPhysicalDeviceMemoryProperties p{};
    vkGetPhysicalDeviceMemoryProperties(device, &p);
    for (uint32_t i = 0; i < p.memoryTypeCount; ++i)
        if ((bits & (1u << i)) && (p.memoryTypes[i].propertyFlags & wanted) == wanted) {
            *index = i;
            return true;
        }
    return false;
}

XrResult CreateImages(Swapchain& sc, VkImageUsageFlags usage, VkImageCreateFlags flags,
                      uint32_t count) {
    Session& s = *sc.session;
    for (uint32_t i = 0; i < count; ++i) {
        auto ci = VkInit<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
        ci.flags = flags;
        ci.imageType = VK_IMAGE_TYPE_2D;
        ci.format = sc.format;
        ci.extent = {sc.info.width, sc.info.height, 1};
        ci.mipLevels = sc.info.mipCount;
        ci.arrayLayers = sc.info.arraySize;
        ci.samples = VK_SAMPLE_COUNT_1_BIT;
        ci.tiling = VK_IMAGE_TILING_OPTIMAL;
        ci.usage = usage;
        ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
        ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        Swapchain::Image image;
        XRRT_VK(vkCreateImage(s.device, &ci, nullptr, &image.image));
        sc.images.push_back(image);
        VkMemoryRequirements req{};
        vkGetImageMemoryRequirements(s.device, image.image, &req);
        auto alloc = VkInit<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
        alloc.allocationSize = req.size;
        if (!MemoryType(s.physicalDevice, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT,
                        &alloc.memoryTypeIndex) &&
            !MemoryType(s.physicalDevice, req.memoryTypeBits, 0, &alloc.memoryTypeIndex))
            return XR_ERROR_RUNTIME_FAILURE;
        XRRT_VK(vkAllocateMemory(s.device, &alloc, nullptr, &sc.images.back().memory));
        XRRT_VK(vkBindImageMemory(s.device, image.image, sc.images.back().memory, 0));
    }
    return XR_SUCCESS;
}

XrResult XRAPI_CALL CreateSwapchain(XrSession handle, const XrSwapchainCreateInfo* info,
                                    XrSwapchain* out) {
    return OnRunningSession(handle, [&](Session* s) -> XrResult {
        if (!info || !out || info->type != XR_TYPE_SWAPCHAIN_CREATE_INFO)
            return XR_ERROR_VALIDATION_FAILURE;
        std::vector<VkFormat> formats = SupportedFormats(s->physicalDevice);
        auto format = VkFormat(info->format);
        if (std::find(formats.begin(), formats.end(), format) == formats.end())
            return XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED;
        if (info->width == 0 || info->height == 0 || info->width > kMaxImageSize ||
            info->height > kMaxImageSize || info->arraySize == 0 || info->mipCount == 0 ||
            info->sampleCount == 0)
            return XR_ERROR_VALIDATION_FAILURE;
        if (info->sampleCount != 1 || info->faceCount != 1 ||
            (info->createFlags & XR_SWAPCHAIN_CREATE_PROTECTED_CONTENT_BIT) ||
            (info->usageFlags & XR_SWAPCHAIN_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT))
            return XR_ERROR_FEATURE_UNSUPPORTED;
        VkImageUsageFlags usage = kRuntimeUsage;
        VkImageCreateFlags flags = 0;
        if (info->usageFlags & XR_SWAPCHAIN_USAGE_UNORDERED_ACCESS_BIT) usage |= VK_IMAGE_USAGE_STORAGE_BIT;
        if (info->usageFlags & XR_SWAPCHAIN_USAGE_TRANSFER_DST_BIT) usage |= VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        if (info->usageFlags & XR_SWAPCHAIN_USAGE_SAMPLED_BIT) usage |= VK_IMAGE_USAGE_SAMPLED_BIT;
        if (info->usageFlags & XR_SWAPCHAIN_USAGE_INPUT_ATTACHMENT_BIT_KHR)
            usage |= VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT;
        if (info->usageFlags & XR_SWAPCHAIN_USAGE_MUTABLE_FORMAT_BIT)
            flags |= VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT;
        // The usage must be possible for this format (e.g. STORAGE on an sRGB format often is not).
        VkImageFormatProperties limits{};
        if (vkGetPhysicalDeviceImageFormatProperties(s->physicalDevice, format, VK_IMAGE_TYPE_2D,
                                                     VK_IMAGE_TILING_OPTIMAL, usage, flags,
                                                     &limits) != VK_SUCCESS ||
            info->width > limits.maxExtent.width || info->height > limits.maxExtent.height ||
            info->arraySize > limits.maxArrayLayers || info->mipCount > limits.maxMipLevels)
            return XR_ERROR_FEATURE_UNSUPPORTED;
        auto sc = std::make_unique<Swapchain>();
        sc->session = s;
        sc->info = *info;
        sc->info.next = nullptr;
        sc->format = format;
        bool isStatic = info->createFlags & XR_SWAPCHAIN_CREATE_STATIC_IMAGE_BIT;
        XrResult r = CreateImages(*sc, usage, flags, isStatic ? 1 : kSwapchainImageCount);
        Swapchain* raw = sc.release();
        TheRuntime().swapchains.insert(raw);
        s->swapchains.push_back(raw);
        if (XR_FAILED(r)) {
            DestroySwapchainObject(raw);
            return r;
        }
        *out = ToHandle<XrSwapchain>(raw);
        return XR_SUCCESS;
    });
}

XrResult XRAPI_CALL DestroySwapchain(XrSwapchain handle) {
    return DestroyHandle(TheRuntime().swapchains, handle, DestroySwapchainObject);
}

XrResult CheckSwapchain(XrSwapchain handle, Swapchain** out, XrResult* gate) {
    Swapchain* sc = Find(TheRuntime().swapchains, handle);
    if (!sc) return XR_ERROR_HANDLE_INVALID;
    if (sc->session->instance->lost) return XR_ERROR_INSTANCE_LOST;
    *gate = SessionGate(*sc->session);
    if (XR_FAILED(*gate)) return *gate;
    *out = sc;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL EnumerateSwapchainImages(XrSwapchain handle, uint32_t capacity,
                                             uint32_t* count, XrSwapchainImageBaseHeader* images) {
    auto lock = LockApi();
    Swapchain* sc = nullptr;
    XrResult gate = XR_SUCCESS;
    if (XrResult r = CheckSwapchain(handle, &sc, &gate); XR_FAILED(r)) return r;
    auto* vkImages = reinterpret_cast<XrSwapchainImageVulkan2KHR*>(images);
    if (vkImages && capacity > 0 && vkImages[0].type != XR_TYPE_SWAPCHAIN_IMAGE_VULKAN2_KHR)
        return XR_ERROR_VALIDATION_FAILURE;
    XrResult r = TwoCall(capacity, count, vkImages, uint32_t(sc->images.size()),
                         [&](XrSwapchainImageVulkan2KHR& image, uint32_t i) {
                             image.image = sc->images[i].image;
                         });
    return XR_FAILED(r) ? r : gate;
}

// UNDEFINED -> COLOR_ATTACHMENT_OPTIMAL on the application's queue (allowed in acquire).
XrResult InitialiseLayout(Swapchain& sc, Swapchain::Image& image) {
    Session& s = *sc.session;
    VkCommandBuffer cmd = s.commandBuffer;
    XRRT_VK(vkResetCommandBuffer(cmd, 0));
    auto begin = VkInit<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    XRRT_VK(vkBeginCommandBuffer(cmd, &begin));
    auto barrier = VkInit<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
    barrier.srcAccessMask = 0;
    barrier.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    barrier.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    barrier.newLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image.image;
    barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, VK_REMAINING_MIP_LEVELS, 0,
                                VK_REMAINING_ARRAY_LAYERS};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                         VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0, nullptr, 1,
                         &barrier);
    XRRT_VK(vkEndCommandBuffer(cmd));
    if (XrResult r = SubmitAndWait(s, cmd); XR_FAILED(r)) return r;
    image.initialised = true;
    return XR_SUCCESS;
}

XrResult XRAPI_CALL AcquireSwapchainImage(XrSwapchain handle,
                                          const XrSwapchainImageAcquireInfo* info,
                                          uint32_t* index) {
    auto lock = LockApi();
    Swapchain* sc = nullptr;
    XrResult gate = XR_SUCCESS;
    if (XrResult r = CheckSwapchain(handle, &sc, &gate); XR_FAILED(r)) return r;
    if ((info && info->type != XR_TYPE_SWAPCHAIN_IMAGE_ACQUIRE_INFO) || !index)
        return XR_ERROR_VALIDATION_FAILURE;
    bool isStatic = sc->info.createFlags & XR_SWAPCHAIN_CREATE_STATIC_IMAGE_BIT;
    if ((isStatic && sc->staticImageAcquired) || sc->acquired.size() == sc->images.size())
        return XR_ERROR_CALL_ORDER_INVALID;
    uint32_t i = sc->nextIndex;
    sc->nextIndex = (sc->nextIndex + 1) % uint32_t(sc->images.size());
    if (!sc->images[i].initialised)
        if (XrResult r = InitialiseLayout(*sc, sc->images[i]); XR_FAILED(r)) return r;
    sc->acquired.push_back({i, false});
    sc->staticImageAcquired = true;
    *index = i;
    return gate;
}

XrResult XRAPI_CALL WaitSwapchainImage(XrSwapchain handle, const XrSwapchainImageWaitInfo* info) {
    auto lock = LockApi();
    Swapchain* sc = nullptr;
    XrResult gate = XR_SUCCESS;
    if (XrResult r = CheckSwapchain(handle, &sc, &gate); XR_FAILED(r)) return r;
    if (!info || info->type != XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO) return XR_ERROR_VALIDATION_FAILURE;
    // The oldest acquired image not yet waited on; the runtime never holds an image, so it is
    // ready at once.
    for (Swapchain::Acquired& a : sc->acquired)
        if (!a.waited) {
            a.waited = true;
            return gate;
        }
    return XR_ERROR_CALL_ORDER_INVALID;
}

XrResult XRAPI_CALL ReleaseSwapchainImage(XrSwapchain handle,
                                          const XrSwapchainImageReleaseInfo* info) {
    auto lock = LockApi();
    Swapchain* sc = nullptr;
    XrResult gate = XR_SUCCESS;
    if (XrResult r = CheckSwapchain(handle, &sc, &gate); XR_FAILED(r)) return r;
    if (info && info->type != XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO)
        return XR_ERROR_VALIDATION_FAILURE;
    if (sc->acquired.empty() || !sc->acquired.front().waited) return XR_ERROR_CALL_ORDER_INVALID;
    sc->lastReleased = int32_t(sc->acquired.front().index);
    sc->acquired.pop_front();
    return gate;
}

}  // namespace

void DestroySwapchainObject(Swapchain* sc) {
    Session& s = *sc->session;
    for (Swapchain::Image& image : sc->images) {
        if (image.image) vkDestroyImage(s.device, image.image, nullptr);
        if (image.memory) vkFreeMemory(s.device, image.memory, nullptr);
    }
    s.swapchains.erase(std::remove(s.swapchains.begin(), s.swapchains.end(), sc),
                       s.swapchains.end());
    TheRuntime().swapchains.erase(sc);
    delete sc;
}

const char* VkFormatName(VkFormat format) {
    switch (format) {
        case VK_FORMAT_R8G8B8A8_SRGB: return "VK_FORMAT_R8G8B8A8_SRGB";
        case VK_FORMAT_B8G8R8A8_SRGB: return "VK_FORMAT_B8G8R8A8_SRGB";
        case VK_FORMAT_R8G8B8A8_UNORM: return "VK_FORMAT_R8G8B8A8_UNORM";
        case VK_FORMAT_B8G8R8A8_UNORM: return "VK_FORMAT_B8G8R8A8_UNORM";
        case VK_FORMAT_R16G16B16A16_SFLOAT: return "VK_FORMAT_R16G16B16A16_SFLOAT";
        default: return "VK_FORMAT_UNDEFINED";
    }
}

void AddSwapchainFunctions(ApiTable& t) {
    t.insert(t.end(), {
        XRRT_CORE(EnumerateSwapchainFormats), XRRT_CORE(CreateSwapchain), XRRT_CORE(DestroySwapchain),
        XRRT_CORE(EnumerateSwapchainImages), XRRT_CORE(AcquireSwapchainImage),
        XRRT_CORE(WaitSwapchainImage), XRRT_CORE(ReleaseSwapchainImage)
    });
}

}  // namespace fovrt::xrrt
