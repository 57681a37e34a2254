// SPDX-License-Identifier: MIT
// The frame path: compositing layers, frames in flight, and a readback of only what was asked.
#include "gpu_fixture.h"
#include "scenes.h"

#include <glm/gtc/packing.hpp>

#include <cmath>

namespace sky::testscenes
{
namespace
{

class FramePath : public GpuFixture
{
};

float half(uint16_t h) { return glm::unpackHalf1x16(h); }

// The sky and cloud layers are what an image generator composites over its own scene: the sky alone,
// then the clouds premultiplied (aerial perspective applied). Over each other they must give back the
// linear frame the composite made, and the cloud layer's alpha must be the cloud image's.
TEST_F(FramePath, SkyAndCloudLayersRebuildTheLinearFrame)
{
    setWeather(*renderer, reprojectionWeather());
    ViewRequest view = reprojectionView();
    view.readback = kReadEverything | kReadSky | kReadCloudLayer;
    const RenderResult r = renderOk(view, testQuality());
    const size_t pixels = size_t(view.width) * view.height;
    ASSERT_EQ(r.skyRgbaHalf.size(), pixels * 4);
    ASSERT_EQ(r.cloudLayerRgbaHalf.size(), pixels * 4);
    ASSERT_EQ(r.linearRgbaHalf.size(), pixels * 4);
    size_t cloudy = 0, clear = 0;
    double worst = 0;
    for (size_t i = 0; i < pixels; ++i)
    {
        const float a = half(r.cloudLayerRgbaHalf[i * 4 + 3]);
        ASSERT_EQ(r.cloudLayerRgbaHalf[i * 4 + 3], r.cloudRgbaHalf[i * 4 + 3]) << "pixel " << i;
        cloudy += a > 0.5f;
        clear += a == 0.0f;
        for (size_t c = 0; c < 3; ++c)
        {
            const double sky = half(r.skyRgbaHalf[i * 4 + c]);
            const double cloud = half(r.cloudLayerRgbaHalf[i * 4 + c]);
            const double linear = half(r.linearRgbaHalf[i * 4 + c]);
            const double rebuilt = sky * (1.0 - double(a)) + cloud;
            // Three half-float roundings (2^-11 each) of values of the same size.
            worst = std::max(worst, std::abs(rebuilt - linear) / std::max(linear, 1e-3));
            if (a == 0.0f)
            {
                EXPECT_EQ(r.skyRgbaHalf[i * 4 + c], r.linearRgbaHalf[i * 4 + c]) << "clear pixel " << i;
            }
        }
    }
    EXPECT_LT(worst, 4e-3);
    // The view holds both cloud and clear sky, so neither layer is trivially empty or full.
    EXPECT_GT(cloudy, pixels / 50);
    EXPECT_GT(clear, pixels / 50);
}

// A reprojected frame's cloud image (written by the composite from the fresh pixels and the packed
// history) is the one it composited: its alpha and depth are the layers' (and sky * (1 - a) + layer is the
// linear frame, checked above for full frames).
TEST_F(FramePath, ReprojectedLayersMatchTheCloudImage)
{
    setWeather(*renderer, reprojectionWeather());
    ViewRequest view = reprojectionView();
    view.readback = kReadEverything | kReadCloudLayer;
    RenderResult r;
    for (int k = 0; k < 3; ++k)  // history from earlier frames in the image
        r = renderOk(view, reprojectedQuality());
    const size_t pixels = size_t(view.width) * view.height;
    ASSERT_EQ(r.cloudRgbaHalf.size(), pixels * 4);
    ASSERT_EQ(r.cloudDepthM.size(), pixels);
    size_t cloudy = 0;
    double depthSum = 0;
    for (size_t i = 0; i < pixels; ++i)
    {
        ASSERT_EQ(r.cloudLayerRgbaHalf[i * 4 + 3], r.cloudRgbaHalf[i * 4 + 3]) << "pixel " << i;
        ASSERT_TRUE(std::isfinite(r.cloudDepthM[i]) && r.cloudDepthM[i] >= 0.0f) << "pixel " << i;
        if (half(r.cloudRgbaHalf[i * 4 + 3]) > 0.5f)
        {
            ++cloudy;
            depthSum += double(r.cloudDepthM[i]);
        }
    }
    EXPECT_GT(cloudy, pixels / 50);
    // The layer's base is 1 km above the eye, 12 degrees up: its clouds are kilometres away. (A pixel's
    // depth may be 0 where the reconstruction filled it from fresh pixels that saw no cloud.)
    EXPECT_GT(depthSum / double(std::max<size_t>(cloudy, 1)), 2000.0);
}

// Frames in flight: two frames submitted before either is collected give the bytes of the same two
// frames rendered one after the other (reprojected: the second reprojects the first).
TEST_F(FramePath, FramesInFlightEqualFramesOneByOne)
{
    setWeather(*renderer, reprojectionWeather());
    ViewRequest a = reprojectionView();
    ViewRequest b = a;
    b.pose.headingDeg += 1.0;
    b.readback = kReadDisplay | kReadDepth;
    const QualitySettings quality = reprojectedQuality();

    // The same march phase for both sequences (it follows the reprojected frames' count).
    dropHistory(*renderer);
    renderer->reconstruct.reprojection.frameIndex = 0;
    const RenderResult oneA = renderOk(a, quality);
    const RenderResult oneB = renderOk(b, quality);

    dropHistory(*renderer);
    renderer->reconstruct.reprojection.frameIndex = 0;
    FrameTicket ticketA, ticketB;
    ASSERT_TRUE(submitView(*renderer, a, quality, ticketA).ok());
    ASSERT_TRUE(submitView(*renderer, b, quality, ticketB).ok());
    EXPECT_NE(ticketA.context, ticketB.context);
    RenderResult inFlightA, inFlightB;
    ASSERT_TRUE(finishView(*renderer, ticketA, inFlightA).ok());
    ASSERT_TRUE(finishView(*renderer, ticketB, inFlightB).ok());
    EXPECT_EQ(inFlightA.displayRgba8, oneA.displayRgba8);
    EXPECT_EQ(inFlightA.cloudRgbaHalf, oneA.cloudRgbaHalf);
    EXPECT_EQ(inFlightB.displayRgba8, oneB.displayRgba8);
    EXPECT_EQ(inFlightB.cloudDepthM, oneB.cloudDepthM);
    EXPECT_NE(oneA.displayRgba8, oneB.displayRgba8);
}

// A reprojected frame that asks for the display only makes and reads back nothing else: no full-resolution
// cloud image on the GPU, the display's bytes in the readback buffer, no pixels of other images on the host.
TEST_F(FramePath, ReadsBackOnlyWhatWasAskedFor)
{
    Renderer own;
    RendererOptions options;
    options.context.validation = true;
    options.context.quiet = true;
    ASSERT_TRUE(createRenderer(own, options).ok());
    setWeather(own, reprojectionWeather());
    ViewRequest view = reprojectionView();
    view.readback = kReadDisplay;
    view.linearOutput = false;
    QualitySettings quality = reprojectedQuality();
    RenderResult r;
    ASSERT_TRUE(renderView(own, view, quality, r).ok());
    EXPECT_EQ(r.displayRgba8.size(), size_t(view.width) * view.height * 4);
    EXPECT_TRUE(r.cloudRgbaHalf.empty());
    EXPECT_TRUE(r.cloudDepthM.empty());
    EXPECT_TRUE(r.linearRgbaHalf.empty());
    EXPECT_EQ(own.march.cloudImage.image, VkImage(VK_NULL_HANDLE));
    EXPECT_EQ(own.composite.skyImage.image, VkImage(VK_NULL_HANDLE));
    {
        std::lock_guard<std::mutex> lock(own.memory.mutex);
        // One frame context has read back (the display, 16-byte aligned), the other nothing yet.
        EXPECT_LE(own.memory.hostReadbackBytes, 2 * readbackBytes(own.composite.displayImage) + 65536);
    }
    // Asking for a layer later makes its image; the next display-only frame lets it go again.
    view.readback = kReadDisplay | kReadSky;
    ASSERT_TRUE(renderView(own, view, quality, r).ok());
    EXPECT_NE(own.composite.skyImage.image, VkImage(VK_NULL_HANDLE));
    EXPECT_EQ(r.skyRgbaHalf.size(), size_t(view.width) * view.height * 4);
    view.readback = kReadDisplay;
    ASSERT_TRUE(renderView(own, view, quality, r).ok());
    EXPECT_EQ(own.composite.skyImage.image, VkImage(VK_NULL_HANDLE));
    EXPECT_TRUE(r.skyRgbaHalf.empty());
    EXPECT_EQ(own.ctx.validationMessages.load(), 0u);
    destroyRenderer(own);
}

}  // namespace
}  // namespace sky::testscenes
