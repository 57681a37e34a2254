// SPDX-License-Identifier: MIT
#include "skyservice/weather/renderer_weather.h"

#include "shaders/shared/weather_window.h"
#include "skyservice/weather/column_bounds.h"

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
    ImageDesc bounds;
    bounds.format = VK_FORMAT_R8G8_UINT;  // shaders/shared/column_bounds.h
    bounds.width = columnBoundsWidth(WEATHER_WINDOW_SIZE);
    bounds.height = WEATHER_WINDOW_SIZE;
    bounds.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    SKY_TRY(createImage(ctx, memory, w.columnBoundsImage, bounds, "weather column bounds"));
    return createWindowCopy(ctx, w.copy);
}

void destroyWeatherImages(const Context& ctx, MemoryTracker& memory, RendererWeather& w)
{
    destroyWindowCopy(ctx, memory, w.copy);
    destroyImage(ctx, memory, w.windowImage);
    destroyImage(ctx, memory, w.columnBoundsImage);
}

}  // namespace sky
