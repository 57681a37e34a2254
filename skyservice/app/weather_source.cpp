// SPDX-License-Identifier: MIT
#include "skyservice/app/weather_source.h"

#include "skyservice/sky/builtin_weather.h"
#include "weather_ingest/weather_timeline.h"

namespace sky
{

bool loadWeatherSource(const std::string& source, int64_t unixTimeS, WeatherSnapshot& out, std::string& error)
{
    if (source == "builtin")
    {
        out = makeBuiltinWeather(unixTimeS);
        return true;
    }
    WeatherTimeline timeline;
    if (!timeline.loadFile(source, error))
        return false;
    out = timeline.sample(double(unixTimeS));
    return true;
}

}  // namespace sky
