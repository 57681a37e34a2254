// SPDX-License-Identifier: MIT
// The two shader variants (shaders/shared/bindings.h PARAMS_BLOCK): parameters read from uniform
// buffers (GPUs) or from storage buffers (lavapipe, which leaks with uniform buffers) draw the same
// frame byte for byte, with validation on. CI runs on lavapipe, where Auto picks the storage variant:
// this is the test that keeps the uniform variant, the one GPUs run, valid.
#include "skyservice/render/renderer.h"
#include "tests/gpu/scenes.h"

#include <gtest/gtest.h>

using namespace sky;
using namespace sky::testscenes;

namespace
{

RenderResult renderWith(ContextOptions::ParamBlocks blocks, bool& storage, uint32_t& validationMessages)
{
    Renderer r;
    RendererOptions options;
    options.context.validation = true;
    options.context.quiet = true;
    options.context.paramBlocks = blocks;
    options.noiseSeed = 7;
    RenderResult result;
    SkyStatus s = createRenderer(r, options);
    EXPECT_TRUE(s.ok()) << s.message;
    if (s.ok())
    {
        setWeather(r, uniformLayer(0.5f, CloudType::Cumulus, 1200.0f, 2600.0f));
        ViewRequest v = lookUp(45.0, 7.0, 300.0, 10.0, "2026-06-21T12:00:00Z");
        v.width = 64;
        v.height = 36;
        v.shadowMap = true;
        v.shadowMapSize = 32;
        QualitySettings q = testQuality();
        s = renderView(r, v, q, result);
        EXPECT_TRUE(s.ok()) << s.message;
        q.reprojected = true;
        RenderResult reprojected;
        s = renderView(r, v, q, reprojected);  // the reconstruct pass too
        EXPECT_TRUE(s.ok()) << s.message;
    }
    storage = r.ctx.paramsInStorageBuffers;
    validationMessages = r.ctx.validationMessages.load();
    destroyRenderer(r);
    return result;
}

}  // namespace

TEST(ParamBlocks, UniformAndStorageVariantsDrawTheSameFrame)
{
    bool uniformIsStorage = true, storageIsStorage = false;
    uint32_t uniformMessages = 1, storageMessages = 1;
    RenderResult u = renderWith(ContextOptions::ParamBlocks::Uniform, uniformIsStorage, uniformMessages);
    RenderResult s = renderWith(ContextOptions::ParamBlocks::Storage, storageIsStorage, storageMessages);
    EXPECT_FALSE(uniformIsStorage);
    EXPECT_TRUE(storageIsStorage);
    EXPECT_EQ(uniformMessages, 0u) << "validation messages with uniform parameter blocks";
    EXPECT_EQ(storageMessages, 0u) << "validation messages with storage parameter blocks";
    ASSERT_FALSE(u.displayRgba8.empty());
    EXPECT_EQ(u.displayRgba8, s.displayRgba8);
    EXPECT_EQ(u.cloudRgbaHalf, s.cloudRgbaHalf);
    EXPECT_EQ(u.shadowTransmittance, s.shadowTransmittance);
}
