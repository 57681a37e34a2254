// SPDX-License-Identifier: MIT
// Builds the per-frame uniform block (shaders/shared/frame_params.h) on the CPU, in double, from the
// camera, the sun and moon, the weather window, the quality settings, the reprojection state, the
// outputs asked for and the frame's place in an accumulation: the one place that assembles it.
#pragma once

#include "shaders/shared/frame_params.h"
#include "skyservice/render/frame_outputs.h"
#include "skyservice/render/render_tuning.h"
#include "skyservice/render/render_types.h"
#include "skyservice/weather/window_lattice.h"
#include "skyservice/weather/window_analysis.h"
#include "skyservice/sky/ephemeris.h"

#include <optional>

namespace sky
{

struct FrameInputs
{
    const CameraFrame* camera = nullptr;
    const SunMoon* sunMoon = nullptr;
    const WeatherWindow* window = nullptr;
    const WindowSummary* summary = nullptr;
    EyeOnWindow eyeOnWindow;        ///< where the eye lies on `window` (its centre is the eye's lattice node)
    const ViewRequest* request = nullptr;
    const QualitySettings* quality = nullptr;
    const RenderTuning* tuning = nullptr;  ///< null: the defaults
    double animationTimeS = 0;      ///< seconds since the weather's valid time (drives wind drift)
    /// ENU -> ECEF rotation at a point fixed with the weather (the centre of its grid): the wind drift is
    /// turned into earth-fixed axes there, not at the eye, so clouds do not slide as the eye moves.
    glm::dmat3 driftEnuToEcef{1.0};
    glm::dvec3 sunIrradiance{1.0};  ///< top-of-atmosphere solar irradiance (renderer units)
    glm::dvec3 ambientSkyRadiance{0.0};   ///< mean sky radiance above the cloud layers
    glm::dvec3 groundIrradiance{0.0};     ///< irradiance reaching the ground
    double groundAlbedo = 0.3;
    double exposure = 1.0;
    FrameOutputs outputs;           ///< the composite's optional outputs (FRAME_FLAG_* for them)
    /// Reprojected frames: the block, its phase and the previous camera (reprojection.h
    /// reprojectionParams). Empty: every pixel marched, no history.
    std::optional<ReprojectionParams> reprojection;
    /// Accumulation (offline quality): frame `accumulationIndex` of `accumulationFrames`, each with new
    /// march jitter and a sub-pixel offset of the view rays.
    uint32_t accumulationIndex = 0;
    uint32_t accumulationFrames = 1;
};

/// The whole uniform block of a frame from its named inputs; the light volume's placement
/// (light_volume.h placeLightVolume) is made here too, from the eye's window-plane position, the cloud
/// shell and the rays the march block leaves.
FrameParams makeFrameParams(const FrameInputs& in);

/// The noise offsets are taken modulo this period (m): every noise period must divide it (see
/// validateNoisePeriods), so the offsets stay small in float and the clouds stay world-fixed.
double noiseOffsetModulusM(const QualitySettings& quality);
bool validateNoisePeriods(const QualitySettings& quality, std::string& error);

}  // namespace sky
