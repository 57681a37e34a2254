// SPDX-License-Identifier: MIT
#include "skyservice/app/look_views.h"

#include "skyservice/sky/builtin_weather.h"
#include "skyservice/sky/ephemeris.h"

#include <cmath>

namespace sky
{
namespace
{

LookView look(const char* name, const char* caption, const EyePose& pose, double fovYDeg, const char* timeIso)
{
    LookView v{name, caption, pose, fovYDeg, 0};
    std::string error;
    parseIso8601Utc(timeIso, v.unixTimeS, error);
    return v;
}

}  // namespace

std::vector<LookView> lookViews()
{
    const double cuLat = 44.3, cuLon = 7.5;  // inside the built-in cumulus field (client_demo's start)
    const double cbLat = kBuiltinCumulonimbusLatDeg, cbLon = kBuiltinCumulonimbusLonDeg;
    return {
        look("look-under-cumulus", "Under cumulus at noon: 500 m, pitch 10 deg, 44.3N 7.5E",
             {cuLat, cuLon, 500.0, 0.0, 10.0, 0.0}, 60.0, "2026-06-21T11:30:00Z"),
        // 1.6 km east of client_demo's start: with the domed cumulus its start at 1500 m is inside a cloud.
        look("look-among-cumulus", "Among cumulus at base level: 1500 m, in a gap",
             {cuLat, cuLon + 0.02, 1500.0, 0.0, 0.0, 0.0}, 60.0, "2026-06-21T16:00:00Z"),
        look("look-cumulus-above", "Cumulus from above: 4000 m, sun behind", {cuLat, cuLon, 4000.0, 0.0, -15.0, 0.0},
             60.0, "2026-06-21T11:30:00Z"),
        look("look-cumulonimbus-20km", "Cumulonimbus and anvil from 20 km, 3600 m",
             {cbLat, cbLon - lonOffsetDeg(20000.0, cbLat), 3600.0, 90.0, 12.0, 0.0}, 70.0, "2026-06-21T15:00:00Z"),
        look("look-anvil-fl400", "The anvil from FL400, 30 km west of the tower",
             {cbLat, cbLon - lonOffsetDeg(30000.0, cbLat), 12200.0, 90.0, -12.0, 0.0}, 60.0, "2026-06-21T15:00:00Z"),
        look("look-sunset-cumulus", "Sunset behind cumulus: 800 m, towards the sun",
             {44.5, cuLon, 800.0, 302.0, 6.0, 0.0}, 60.0, "2026-06-21T18:55:00Z"),
        look("look-inside-stratus", "Inside the stratocumulus deck at 1300 m",
             {kBuiltinDeckLatDeg, kBuiltinDeckLonDeg, 1300.0, 45.0, 0.0, 0.0}, 60.0, "2026-06-21T10:00:00Z"),
    };
}

const LookView* findLookView(const std::vector<LookView>& views, const std::string& name)
{
    for (const LookView& v : views)
        if (v.name == name)
            return &v;
    return nullptr;
}

ViewRequest lookViewRequest(const LookView& view, uint32_t width, uint32_t height)
{
    ViewRequest r;
    r.pose = view.pose;
    r.fovYDeg = view.fovYDeg;
    r.width = width;
    r.height = height;
    r.unixTimeS = view.unixTimeS;
    return r;
}

double lonOffsetDeg(double metres, double latDeg)
{
    return metres / (111320.0 * std::cos(latDeg * M_PI / 180.0));
}

}  // namespace sky
