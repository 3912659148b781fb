// The "compositor": at xrEndFrame it copies each projection view's released image rect into a
// host-visible buffer on the application's queue (the spec has the application synchronise that
// queue around xrEndFrame) and waits; with FOVRT_TEST_XR_DUMP=DIR it writes
//   DIR/frame_%05u_eye%u.ppm  binary P6 RGB8 of the stored bytes (B8G8R8A8 swizzled to RGB; sRGB
//                              formats undecoded; R16G16B16A16_SFLOAT as round(clamp(v,0,1)*255))
//   DIR/frames.jsonl          one JSON object per xrEndFrame (README.md lists the fields).
#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "runtime.h"

namespace fovrt::xrrt {

namespace {

uint32_t BytesPerPixel(VkFormat format) { return format == VK_FORMAT_R16G16B16A16_SFLOAT ? 8 : 4; }

float HalfToFloat(uint16_t h) {
    int exponent = (h >> 10) & 0x1f;
    int mantissa = h & 0x3ff;
    float v;
    if (exponent == 0) v = std::ldexp(float(mantissa), -24);
    else if (exponent == 31) v = mantissa ? NAN : INFINITY;
    else v = std::ldexp(float(mantissa | 0x400), exponent - 25);
    return (h & 0x8000) ? -v : v;
}

uint8_t HalfToByte(uint16_t h) {
    float v = HalfToFloat(h);
    if (!(v > 0.0f)) return 0;  // negatives and NaN
    return uint8_t(std::lround(std::min(v, 1.0f) * 255.0f));
}

XrResult EnsureReadback(Session& s, VkDeviceSize size) {
    if (s.readbackSize >= size) return XR_SUCCESS;
    DestroyReadback(s);
    auto ci = VkInit<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    ci.size = size;
    ci.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    XRRT_VK(vkCreateBuffer(s.device, &ci, nullptr, &s.readback));
    VkMemoryRequirements req{};
    vkGetBufferMemoryRequirements(s.device, s.readback, &req);
    VkPhysicalDeviceMemoryProperties props{};
    vkGetPhysicalDeviceMemoryProperties(s.physicalDevice, &props);
    constexpr VkMemoryPropertyFlags kHost =
        VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    auto alloc = VkInit<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = UINT32_MAX;
    for (uint32_t i = 0; i < props.memoryTypeCount; ++i)
        if ((req.memoryTypeBits & (1u << i)) &&
            (props.memoryTypes[i].propertyFlags & kHost) == kHost) {
            alloc.memoryTypeIndex = i;
            break;
        }
    if (alloc.memoryTypeIndex == UINT32_MAX) return XR_ERROR_RUNTIME_FAILURE;
    XRRT_VK(vkAllocateMemory(s.device, &alloc, nullptr, &s.readbackMemory));
    XRRT_VK(vkBindBufferMemory(s.device, s.readback, s.readbackMemory, 0));
    XRRT_VK(vkMapMemory(s.device, s.readbackMemory, 0, VK_WHOLE_SIZE, 0, &s.readbackMapped));
    s.readbackSize = size;
    return XR_SUCCESS;
}

struct ViewCopy {
    const XrCompositionLayerProjectionView* view;
    Swapchain* swapchain;
    uint32_t imageIndex;
    VkDeviceSize offset;
};

void RecordCopy(VkCommandBuffer cmd, VkBuffer buffer, const ViewCopy& c) {
    const XrSwapchainSubImage& sub = c.view->subImage;
    VkImage image = c.swapchain->images[c.imageIndex].image;
    VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, sub.imageArrayIndex, 1};
    auto toSource = VkInit<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
    toSource.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;  // whatever the application wrote
    toSource.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    toSource.oldLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    toSource.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    toSource.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    toSource.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    toSource.image = image;
    toSource.subresourceRange = range;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                         0, 0, nullptr, 0, nullptr, 1, &toSource);
    VkBufferImageCopy region{};
    region.bufferOffset = c.offset;
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, sub.imageArrayIndex, 1};
    region.imageOffset = {sub.imageRect.offset.x, sub.imageRect.offset.y, 0};
    region.imageExtent = {uint32_t(sub.imageRect.extent.width),
                          uint32_t(sub.imageRect.extent.height), 1};
    vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &region);
    VkImageMemoryBarrier back = toSource;  // returned in the layout the application expects
    back.srcAccessMask = 0;
    back.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    back.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    back.newLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                         0, 0, nullptr, 0, nullptr, 1, &back);
}

XrResult CopyViews(Session& s, const std::vector<ViewCopy>& copies, VkDeviceSize total) {
    if (XrResult r = EnsureReadback(s, total); XR_FAILED(r)) return r;
    VkCommandBuffer cmd = s.commandBuffer;
    XRRT_VK(vkResetCommandBuffer(cmd, 0));
    auto begin = VkInit<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    XRRT_VK(vkBeginCommandBuffer(cmd, &begin));
    for (const ViewCopy& c : copies) RecordCopy(cmd, s.readback, c);
    auto toHost = VkInit<VkBufferMemoryBarrier>(VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER);
    toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    toHost.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    toHost.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    toHost.buffer = s.readback;
    toHost.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0,
                         nullptr, 1, &toHost, 0, nullptr);
    XRRT_VK(vkEndCommandBuffer(cmd));
    return SubmitAndWait(s, cmd);
}

void WritePpm(const std::filesystem::path& file, const ViewCopy& c, const uint8_t* pixels) {
    int w = c.view->subImage.imageRect.extent.width;
    int h = c.view->subImage.imageRect.extent.height;
    VkFormat format = c.swapchain->format;
    bool bgr = format == VK_FORMAT_B8G8R8A8_UNORM || format == VK_FORMAT_B8G8R8A8_SRGB;
    std::vector<uint8_t> rgb(size_t(w) * h * 3);
    for (size_t i = 0; i < size_t(w) * h; ++i) {
        if (format == VK_FORMAT_R16G16B16A16_SFLOAT) {
            uint16_t half[4];
            std::memcpy(half, pixels + i * 8, sizeof half);
            for (int k = 0; k < 3; ++k) rgb[i * 3 + k] = HalfToByte(half[k]);
        } else {
            const uint8_t* p = pixels + i * 4;
            rgb[i * 3 + 0] = bgr ? p[2] : p[0];
            rgb[i * 3 + 1] = p[1];
            rgb[i * 3 + 2] = bgr ? p[0] : p[2];
        }
    }
    std::ofstream out(file, std::ios::binary);
    out << "P6\n" << w << " " << h << "\n255\n";
    out.write(reinterpret_cast<const char*>(rgb.data()), std::streamsize(rgb.size()));
}

nlohmann::json PoseJson(const XrPosef& p) {
    return {{"position", {p.position.x, p.position.y, p.position.z}},
            {"orientation", {p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w}}};
}

}  // namespace

void DestroyReadback(Session& s) {
    if (s.readbackMapped) vkUnmapMemory(s.device, s.readbackMemory);
    if (s.readback) vkDestroyBuffer(s.device, s.readback, nullptr);
    if (s.readbackMemory) vkFreeMemory(s.device, s.readbackMemory, nullptr);
    s.readbackMapped = nullptr;
    s.readback = VK_NULL_HANDLE;
    s.readbackMemory = VK_NULL_HANDLE;
    s.readbackSize = 0;
}

XrResult ReadBackAndDump(Session& s, const XrFrameEndInfo& info, uint64_t frame) {
    // Only the first projection layer is read back (fovrt submits one).
    const XrCompositionLayerProjection* projection = nullptr;
    for (uint32_t i = 0; i < info.layerCount && !projection; ++i)
        if (info.layers[i]->type == XR_TYPE_COMPOSITION_LAYER_PROJECTION)
            projection = reinterpret_cast<const XrCompositionLayerProjection*>(info.layers[i]);
    std::vector<ViewCopy> copies;
    VkDeviceSize total = 0;
    if (projection) {
        for (uint32_t v = 0; v < projection->viewCount; ++v) {
            const XrCompositionLayerProjectionView& view = projection->views[v];
            Swapchain* sc = Find(TheRuntime().swapchains, view.subImage.swapchain);
            copies.push_back({&view, sc, uint32_t(sc->lastReleased), total});
            VkDeviceSize bytes = VkDeviceSize(view.subImage.imageRect.extent.width) *
                                 view.subImage.imageRect.extent.height *
                                 BytesPerPixel(sc->format);
            total += (bytes + 15) & ~VkDeviceSize(15);
        }
        if (XrResult r = CopyViews(s, copies, total); XR_FAILED(r)) return r;
    }
    const Config& config = s.instance->config;
    if (config.dumpDir.empty()) return XR_SUCCESS;
    std::filesystem::path dir(config.dumpDir);
    std::error_code ignored;
    std::filesystem::create_directories(dir, ignored);
    nlohmann::json line;
    line["frame"] = frame;
    line["displayTime"] = info.displayTime;
    line["layerCount"] = info.layerCount;
    line["state"] = SessionStateName(s.state);
    line["views"] = nlohmann::json::array();
    for (size_t v = 0; v < copies.size(); ++v) {
        const ViewCopy& c = copies[v];
        char name[64];
        std::snprintf(name, sizeof name, "frame_%05u_eye%u.ppm", unsigned(frame), unsigned(v));
        WritePpm(dir / name, c, static_cast<const uint8_t*>(s.readbackMapped) + c.offset);
        const XrRect2Di& r = c.view->subImage.imageRect;
        line["views"].push_back({
            {"pose", PoseJson(c.view->pose)},
            {"fov", {c.view->fov.angleLeft, c.view->fov.angleRight, c.view->fov.angleUp,
                     c.view->fov.angleDown}},
            {"swapchainSize", {c.swapchain->info.width, c.swapchain->info.height}},
            {"imageRect", {r.offset.x, r.offset.y, r.extent.width, r.extent.height}},
            {"imageArrayIndex", c.view->subImage.imageArrayIndex},
            {"imageIndex", c.imageIndex},
            {"format", VkFormatName(c.swapchain->format)},
            {"ppm", name},
        });
    }
    if (config.gaze == GazeMode::On) {
        glm::vec3 g = GazeDirection(config, info.displayTime);
        line["gaze"] = {g.x, g.y, g.z};
    } else {
        line["gaze"] = nullptr;
    }
    std::ofstream(dir / "frames.jsonl", std::ios::app) << line.dump() << "\n";
    return XR_SUCCESS;
}

}  // namespace fovrt::xrrt
