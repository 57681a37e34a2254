// SPDX-License-Identifier: MIT
#include "skyservice/render/reference_renderer.h"

#include "shaders/shared/column_bounds.h"
#include "shaders/shared/reference_params.h"
#include "skyservice/render/atmosphere_passes.h"
#include "skyservice/weather/column_bounds.h"
#include "skyservice/render/frame_recording.h"

#include <algorithm>
#include <chrono>
#include <cstring>

namespace sky
{
namespace
{

static_assert(sizeof(ReferencePush) == 80, "shaders/shared/reference_params.h: ReferencePush is 5 vec4");
static_assert(sizeof(ReferencePathState) == 128, "shaders/shared/reference_params.h: 8 vec4, std430");

static_assert(sizeof(ReferenceCounters) == 32, "shaders/shared/reference_params.h: 8 uint, std430");

/// The default bound of a render's dispatches (ReferenceSettings::maxDispatches): kMinDispatches plus
/// kDispatchesPerSample per sample per pixel. Each sample of the slowest pixel takes a few dispatches at many
/// samples, but the heavy tail of the paths' lengths makes one pixel's first samples slow: from above the
/// built-in cumulus at 96x54 and 2 samples, 37 dispatches (lavapipe).
constexpr uint32_t kMinDispatches = 256;
constexpr uint32_t kDispatchesPerSample = 16;

uint64_t wide(uint32_t low, uint32_t high)
{
    return uint64_t(high) << 32 | low;
}

/// The largest relative density a layer of genus `type` reaches: genusDensityScale, times 1.5 for the
/// cumulonimbus tower (whose anvilDensity term is at most 1), in shaders/clouds/cloud_density.glsl.
float genusDensityBound(int type)
{
    switch (type)
    {
    case CLOUD_TYPE_STRATUS:
    case CLOUD_TYPE_ALTOSTRATUS:
        return 0.6f;
    case CLOUD_TYPE_STRATOCUMULUS:
    case CLOUD_TYPE_ALTOCUMULUS:
        return 0.8f;
    case CLOUD_TYPE_NIMBOSTRATUS:
        return 1.2f;
    case CLOUD_TYPE_CUMULONIMBUS:
        return 1.2f * 1.5f;
    default:
        return 1.0f;
    }
}

SkyStatus ensureSums(Renderer& r, ReferenceRenderer& ref, uint32_t width, uint32_t height)
{
    if (ref.radianceSum.image && ref.radianceSum.extent.width == width && ref.radianceSum.extent.height == height)
        return SkyStatus::success();
    destroyImage(r.ctx, r.memory, ref.radianceSum);
    destroyImage(r.ctx, r.memory, ref.depthSum);
    destroyBuffer(r.ctx, r.memory, ref.paths);
    SKY_TRY(createBuffer(r.ctx, r.memory, ref.paths, VkDeviceSize(width) * height * sizeof(ReferencePathState),
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::DeviceLocal, "reference paths"));
    ImageDesc d;
    d.width = width;
    d.height = height;
    d.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    d.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    SKY_TRY(createImage(r.ctx, r.memory, ref.radianceSum, d, "reference radiance sum"));
    d.format = VK_FORMAT_R32_SFLOAT;
    SKY_TRY(createImage(r.ctx, r.memory, ref.depthSum, d, "reference depth sum"));
    OneShot shot;
    SKY_TRY(beginOneShot(r.ctx, shot));
    transitionImage(shot.cmd, ref.radianceSum, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    transitionImage(shot.cmd, ref.depthSum, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    return endOneShot(r.ctx, shot);
}

ReferencePush makePush(const Renderer& r, const ReferenceSettings& s)
{
    ReferencePush p{};
    uint32_t flags = 0;
    if (s.slab.enabled)
        flags |= REFERENCE_FLAG_SLAB;
    if (s.unitLight)
        flags |= REFERENCE_FLAG_UNIT_LIGHT;
    if (s.hemisphere != 0)
        flags |= REFERENCE_FLAG_HEMISPHERE | (s.hemisphere < 0 ? REFERENCE_FLAG_HEMISPHERE_DOWN : 0u);
    p.control = uvec4(0u, s.samplesPerPixel, std::min(s.iterationsPerDispatch, 65000u), flags);
    p.limits = uvec4(std::max(1u, s.maxEvents), 0u, 0u, 0u);
    (void)r;
    // The anvil slab: the cumulonimbus genus times its 0.8 in cloudDensity, no rain.
    p.phase = vec4(float(uint32_t(s.phase)), float(s.dropletDiameterUm), float(s.seed), 1.2f * 0.8f);
    p.slab = vec4(float(s.slab.baseM), float(s.slab.topM), float(s.slab.extinctionPerM), float(s.slab.albedo));
    const glm::dvec3 l = glm::normalize(s.unitLightDirectionEnu);
    p.testLight = vec4(float(l.x), float(l.y), float(l.z), 0.0f);
    return p;
}

template <typename T>
SkyStatus readInto(Renderer& r, const Image& image, std::vector<T>& out)
{
    std::vector<uint8_t> bytes;
    SKY_TRY(readbackImage(r.ctx, r.memory, image, bytes));
    out.resize(bytes.size() / sizeof(T));
    std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
    return SkyStatus::success();
}

}  // namespace

static std::vector<glm::vec4> buildLayerBounds(const WeatherWindow& window)
{
    const uint32_t n = window.sizeTexels;
    const uint32_t width = columnBoundsWidth(n);
    std::vector<glm::vec4> atlas(size_t(width) * n, glm::vec4(0.0f));
    // Per texel and layer: the genus bound and the rain factor (rainAbsorptionFactor in
    // shaders/lib/cloud_shape.glsl at the base, where it is largest), where the layer has coverage.
    std::vector<glm::vec4> own(size_t(n) * n, glm::vec4(0.0f));
    std::vector<glm::bvec4> covered(size_t(n) * n, glm::bvec4(false));
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < n; ++i)
            for (uint32_t k = 0; k < MAX_CLOUD_LAYERS; ++k)
            {
                const glm::vec4& layer = window.at(2 * k, i, j);
                const float rain = std::clamp(window.at(2 * k + 1, i, j).z / 20.0f, 0.0f, 1.0f) * 1.5f;
                own[size_t(j) * n + i][int(k)] = genusDensityBound(int(layer.w + 0.5f)) * (1.0f + rain);
                covered[size_t(j) * n + i][int(k)] = layer.x >= CLOUD_COVERAGE_MIN;
            }
    // Level 0: a point in texel c's cell interpolates the coverage and rain of c's 3x3 neighbourhood (as
    // the column bounds count it) and takes its genus from a texel there.
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < n; ++i)
        {
            glm::vec4 bound(0.0f);
            glm::bvec4 any(false);
            for (uint32_t jj = j > 0 ? j - 1 : 0; jj <= std::min(j + 1, n - 1); ++jj)
                for (uint32_t ii = i > 0 ? i - 1 : 0; ii <= std::min(i + 1, n - 1); ++ii)
                {
                    bound = glm::max(bound, own[size_t(jj) * n + ii]);
                    any = glm::bvec4(any.x || covered[size_t(jj) * n + ii].x, any.y || covered[size_t(jj) * n + ii].y,
                                     any.z || covered[size_t(jj) * n + ii].z, any.w || covered[size_t(jj) * n + ii].w);
                }
            atlas[size_t(j) * width + i] = glm::vec4(any.x ? bound.x : 0.0f, any.y ? bound.y : 0.0f,
                                                     any.z ? bound.z : 0.0f, any.w ? bound.w : 0.0f);
        }
    // Coarser levels: the maxima of 2x2 texels of the level below.
    for (int level = 1; level < COLUMN_BOUNDS_LEVELS && (n >> level) > 0; ++level)
    {
        const ivec2 below = columnBoundsLevelOrigin(level - 1, int(n));
        const ivec2 here = columnBoundsLevelOrigin(level, int(n));
        const uint32_t side = n >> level;
        for (uint32_t j = 0; j < side; ++j)
            for (uint32_t i = 0; i < side; ++i)
            {
                glm::vec4 m(0.0f);
                for (uint32_t q = 0; q < 4; ++q)
                {
                    const size_t x = size_t(below.x) + 2 * i + (q & 1);
                    const size_t y = size_t(below.y) + 2 * j + (q >> 1);
                    m = glm::max(m, atlas[y * width + x]);
                }
                atlas[(size_t(here.y) + j) * width + size_t(here.x) + i] = m;
            }
    }
    return atlas;
}

static SkyStatus uploadLayerBounds(Renderer& r, ReferenceRenderer& ref)
{
    if (!r.weather.window)
        return SkyStatus::failure("reference: no weather window", VK_ERROR_INITIALIZATION_FAILED);
    const std::vector<glm::vec4> atlas = buildLayerBounds(r.weather.window->window);
    const uint32_t n = r.weather.window->window.sizeTexels;
    if (!ref.layerBounds.image || ref.layerBounds.extent.height != n)
    {
        destroyImage(r.ctx, r.memory, ref.layerBounds);
        ImageDesc d;
        d.format = VK_FORMAT_R32G32B32A32_SFLOAT;
        d.width = columnBoundsWidth(n);
        d.height = n;
        d.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
        SKY_TRY(createImage(r.ctx, r.memory, ref.layerBounds, d, "reference layer bounds"));
        OneShot shot;
        SKY_TRY(beginOneShot(r.ctx, shot));
        transitionImage(shot.cmd, ref.layerBounds, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
        SKY_TRY(endOneShot(r.ctx, shot));
    }
    return uploadImage(r.ctx, r.memory, ref.layerBounds, atlas.data(), atlas.size() * sizeof(glm::vec4),
                       VK_IMAGE_LAYOUT_GENERAL);
}

SkyStatus createReferenceRenderer(Renderer& r, ReferenceRenderer& ref)
{
    SKY_TRY(createProgram(r.ctx, ref.pathProgram, "reference_path"));
    return createBuffer(r.ctx, r.memory, ref.stats, sizeof(ReferenceCounters), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                        MemoryUse::HostVisible, "reference stats");
}

void destroyReferenceRenderer(Renderer& r, ReferenceRenderer& ref)
{
    if (r.ctx.device)
        vkDeviceWaitIdle(r.ctx.device);
    destroyImage(r.ctx, r.memory, ref.radianceSum);
    destroyImage(r.ctx, r.memory, ref.depthSum);
    destroyImage(r.ctx, r.memory, ref.layerBounds);
    destroyBuffer(r.ctx, r.memory, ref.paths);
    destroyBuffer(r.ctx, r.memory, ref.stats);
    destroyProgram(r.ctx, ref.pathProgram);
}

SkyStatus renderReference(Renderer& r, ReferenceRenderer& ref, const ViewRequest& request,
                          const QualitySettings& quality, const ReferenceSettings& settings, RenderResult& result)
{
    if (settings.samplesPerPixel == 0 || settings.iterationsPerDispatch < 1000)
        return SkyStatus::failure("reference: at least 1 sample per pixel and 1000 iterations per dispatch",
                                  VK_ERROR_INITIALIZATION_FAILED);
    if (settings.slab.enabled && !(settings.slab.topM > settings.slab.baseM && settings.slab.extinctionPerM > 0.0 &&
                                   settings.slab.albedo >= 0.0 && settings.slab.albedo <= 1.0))
        return SkyStatus::failure("reference: the slab needs top > base, extinction > 0 and albedo in [0, 1]",
                                  VK_ERROR_INITIALIZATION_FAILED);
    // The real-time frame: it makes the window, the LUTs of this view and the frame uniforms the path tracer
    // and the composite read (they stay in the frame context until the next frame is recorded).
    QualitySettings q = quality;
    q.reprojected = false;
    q.accumulationFrames = 1;
    SKY_TRY(renderView(r, request, q, result));
    SKY_TRY(ensureSums(r, ref, request.width, request.height));
    SKY_TRY(uploadLayerBounds(r, ref));
    auto* counters = static_cast<ReferenceCounters*>(ref.stats.mapped);
    std::memset(counters, 0, sizeof(ReferenceCounters));

    const FrameContext& frame = recording(r);
    ReferencePush push = makePush(r, settings);
    const auto start = std::chrono::steady_clock::now();
    ref.last = ReferenceStats{};
    ref.last.maxDispatches = settings.maxDispatches > 0
                                 ? settings.maxDispatches
                                 : kMinDispatches + kDispatchesPerSample * settings.samplesPerPixel;
    for (uint32_t k = 0; k < ref.last.maxDispatches; ++k)
    {
        push.control.x = k;
        counters->pixelsUnfinished = 0;
        counters->samplesUnfinished = 0;
        OneShot shot;
        SKY_TRY(beginOneShot(r.ctx, shot));
        dispatch(r.ctx, shot.cmd, ref.pathProgram, request.width, request.height, 1, push,
                 {DescriptorInfo(frame.frameUniforms), DescriptorInfo(frame.atmosphereUniforms),
                  DescriptorInfo(r.weather.windowImage, r.samplers.linearClamp), DescriptorInfo(r.noise.base, r.samplers.linearRepeat),
                  DescriptorInfo(r.noise.detail, r.samplers.linearRepeat), DescriptorInfo(r.noise.curl, r.samplers.linearRepeat),
                  DescriptorInfo(r.atmosphere.transmittanceLut, r.samplers.linearClamp), DescriptorInfo(r.atmosphere.skyViewLut, r.samplers.linearRepeat),
                  DescriptorInfo(r.weather.columnBoundsImage, r.samplers.nearestRepeat), DescriptorInfo(ref.radianceSum),
                  DescriptorInfo(ref.depthSum), DescriptorInfo(r.march.cloudImage), DescriptorInfo(r.march.depthImage),
                  DescriptorInfo(ref.stats), DescriptorInfo(ref.paths),
                  DescriptorInfo(ref.layerBounds, r.samplers.nearestRepeat)});
        SKY_TRY(endOneShot(r.ctx, shot));
        ref.last.dispatches = k + 1;
        if (counters->pixelsUnfinished == 0)
            break;
    }
    ref.last.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ref.last.majorantExceeded = counters->majorantExceeded;
    ref.last.pathsTruncated = counters->pathsTruncated;
    ref.last.pathsCut = counters->samplesUnfinished;
    ref.last.paths = uint64_t(request.width) * request.height * settings.samplesPerPixel - ref.last.pathsCut;
    ref.last.steps = wide(counters->stepsLow, counters->stepsHigh);
    ref.last.stretchesSkipped = wide(counters->skippedLow, counters->skippedHigh);

    // The real-time composite over the path-traced clouds, into the images the frame asked for, wired as
    // a full-resolution frame's. No depth layer: the path tracer finds no front.
    FrameOutputs outputs = FrameOutputs::of(request);
    FrameOutputs composited = outputs;
    composited.depthLayer = false;
    OneShot shot;
    SKY_TRY(beginOneShot(r.ctx, shot));
    const PassFrame f{r.ctx, shot.cmd, frame.frameUniforms, frame.atmosphereUniforms, r.samplers};
    recordComposite(f, r.composite, compositeInputs(r, composited, false), request.width, request.height);
    SKY_TRY(endOneShot(r.ctx, shot));

    if (outputs.display)
        SKY_TRY(readInto(r, r.composite.displayImage, result.displayRgba8));
    if (outputs.cloud)
        SKY_TRY(readInto(r, r.march.cloudImage, result.cloudRgbaHalf));
    if (outputs.depth)
        SKY_TRY(readInto(r, r.march.depthImage, result.cloudDepthM));
    if (outputs.linear)
        SKY_TRY(readInto(r, r.composite.linearImage, result.linearRgbaHalf));
    if (outputs.readSky)
        SKY_TRY(readInto(r, r.composite.skyImage, result.skyRgbaHalf));
    if (outputs.readCloudLayer)
        SKY_TRY(readInto(r, r.composite.cloudLayerImage, result.cloudLayerRgbaHalf));
    result.gpuMs.clear();
    result.gpuMs["reference"] = ref.last.seconds * 1000.0;
    return SkyStatus::success();
}

}  // namespace sky
