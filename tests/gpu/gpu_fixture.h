// SPDX-License-Identifier: MIT
// The fixture every GPU test suite derives from: one Renderer per suite on the available Vulkan device
// (lavapipe in CI) with validation on, and a check after each test that no validation message came.
#pragma once

#include "skyservice/render/renderer.h"

#include <gtest/gtest.h>

namespace sky::testscenes
{

class GpuFixture : public ::testing::Test
{
protected:
    static inline Renderer* renderer = nullptr;

    static void SetUpTestSuite()
    {
        renderer = new Renderer;
        RendererOptions options;
        options.context.validation = true;
        options.context.quiet = true;
        options.noiseSeed = 7;
        SkyStatus s = createRenderer(*renderer, options);
        ASSERT_TRUE(s.ok()) << s.message;
    }
    static void TearDownTestSuite()
    {
        destroyRenderer(*renderer);
        delete renderer;
        renderer = nullptr;
    }
    /// renderView on the suite's renderer; a failure fails the test.
    static RenderResult renderOk(const ViewRequest& view, const QualitySettings& quality)
    {
        RenderResult result;
        SkyStatus s = renderView(*renderer, view, quality, result);
        EXPECT_TRUE(s.ok()) << s.message;
        return result;
    }
    /// renderOk with the renderer's experiment knobs (render_tuning.h) set to `tuning` for this render only.
    static RenderResult renderTuned(const ViewRequest& view, const QualitySettings& quality, const RenderTuning& tuning)
    {
        renderer->tuning = tuning;
        RenderResult result = renderOk(view, quality);
        renderer->tuning = RenderTuning{};
        return result;
    }
    void TearDown() override
    {
        EXPECT_EQ(renderer->ctx.validationMessages.load(), 0u) << "Vulkan validation messages";
    }
};

}  // namespace sky::testscenes
