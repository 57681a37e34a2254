// SPDX-License-Identifier: MIT
#include "skyservice/render/renderer_weather.h"

#include "shaders/shared/weather_window.h"
#include "skyservice/render/column_bounds.h"

namespace sky
{

SkyStatus createWeatherImages(const Context& ctx, MemoryTracker& memory, RendererWeather& w)
{
    ImageDesc d;
    d.viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
    d.format = VK_FORMAT_R16G16B16A16_SFLOAT;  // window_provider.h says why half floats
    d.width = d.height = WEATHER_WINDOW_SIZE;
    d.layers = WEATHER_GPU_SLICES;
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    SKY_TRY(createImage(ctx, memory, w.windowImage, d, "weather window"));
    d = ImageDesc{};
    d.format = VK_FORMAT_R8G8_UINT;  // shaders/shared/column_bounds.h
    d.width = columnBoundsWidth(WEATHER_WINDOW_SIZE);
    d.height = WEATHER_WINDOW_SIZE;
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    return createImage(ctx, memory, w.columnBoundsImage, d, "weather column bounds");
}

void destroyWeatherImages(const Context& ctx, MemoryTracker& memory, RendererWeather& w)
{
    destroyImage(ctx, memory, w.windowImage);
    destroyImage(ctx, memory, w.columnBoundsImage);
}

}  // namespace sky
