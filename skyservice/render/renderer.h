// SPDX-License-Identifier: MIT
// The headless renderer: owns the Vulkan context and every GPU resource, renders one view at a time.
//
// What it holds: the context, the memory tracker and the samplers; one object per pass, each owning its
// program(s), every image it writes and the key of what they hold (NoiseTextures, AtmospherePass,
// LightVolumePass, MarchPass, ReconstructPass, CompositePass, ShadowMapPass: one header each, none of which
// knows the Renderer); the 1x1 stand-ins; the weather in one place (RendererWeather: the snapshot and its
// version, the staged weather, the window and its workers); the frames in flight (FrameContext); and the
// experiment knobs (RenderTuning). A frame is prepared on the CPU by render_view.cpp and recorded by the
// frame function (frame_recording.cpp), the one place that hands each pass its declared inputs: the
// images of the passes before it.
//
// Usage:
//   Renderer r;  createRenderer(r, options)  -> noise and atmosphere tables are built once
//   setWeather(r, snapshot)                  -> the weather to draw (copied), from the next frame on
//   stageWeather(r, snapshot or maker)       -> or: prepared on a worker thread, swapped in when ready
//   renderView(r, request, settings, result) -> pixels back on the host
//   (settings.reprojected: consecutive calls reuse the previous frame; dropHistory(r) forgets it)
//   destroyRenderer(r)
// Every function that can fail at run time returns a SkyStatus naming what failed.
#pragma once

#include "skyservice/render/atmosphere_passes.h"
#include "skyservice/render/composite_pass.h"
#include "skyservice/render/frame_context.h"
#include "skyservice/render/render_tuning.h"
#include "skyservice/render/render_types.h"
#include "skyservice/weather/renderer_weather.h"
#include "skyservice/render/light_volume.h"
#include "skyservice/render/march_pass.h"
#include "skyservice/render/noise_textures.h"
#include "skyservice/render/reconstruct_pass.h"
#include "skyservice/render/pass_frame.h"
#include "skyservice/render/pass_images.h"
#include "skyservice/render/shadow_map.h"
#include "skyservice/render/stand_in_images.h"
#include "skyservice/vk/programs.h"
#include "weather_ingest/weather_snapshot.h"

namespace sky
{

struct RendererOptions
{
    ContextOptions context;
    uint32_t noiseSeed = 1;
};

struct Renderer
{
    Context ctx;
    MemoryTracker memory;
    /// The experiment knobs (render_tuning.h): the defaults, unless a benchmark or a test sets them.
    RenderTuning tuning;

    NoiseTextures noise;          ///< noise_textures.h
    AtmospherePass atmosphere;    ///< the sky's LUTs (atmosphere_passes.h)
    LightVolumePass lightVolume;  ///< the far part of the light cones around the eye (light_volume.h)
    MarchPass march;              ///< the cloud march and its full-resolution images (march_pass.h)
    ReconstructPass reconstruct;  ///< reprojection's reconstruct pass and history (reconstruct_pass.h)
    CompositePass composite;      ///< the display image and the other outputs (composite_pass.h)
    ShadowMapPass shadowPass;     ///< shadow_map.h
    StandInImages standIns;       ///< bound where a pass has nothing to read or write (stand_in_images.h)
    RendererWeather weather;      ///< the weather drawn, its window and their workers (renderer_weather.h)

    /// The per-frame objects (frame_context.h), used in turn; frames[currentFrame] is the one being
    /// recorded, or the last one submitted.
    FrameContext frames[kFramesInFlight];
    uint32_t currentFrame = 0;
    /// Images the passes made for the next frame, initialized at the top of its commands (pass_images.h).
    std::vector<NewImage> newImages;
    Samplers samplers;
};

/// A frame submitted by submitView and not yet collected by finishView.
struct FrameTicket
{
    bool pending = false;
    uint32_t context = 0;       ///< index into Renderer::frames
    ViewRequest request;
    bool reprojected = false;
    bool lightVolume = false;   ///< the frame drew a light volume (gpuMs["lightVolume"])
    FrameReadbackPlan plan;
    ShadowMapReadback shadow;
    RenderResult facts;         ///< what was known at submit time (sun, exposure, weather, march order...)
};

/// The frame context being recorded (its uniform buffers are the ones the passes bind).
inline FrameContext& recording(Renderer& r) { return r.frames[r.currentFrame]; }

SkyStatus createRenderer(Renderer& r, const RendererOptions& options);
void destroyRenderer(Renderer& r);

/// A weather's version is its caller's: the service gives each weather it draws (a load, a CIGI fade
/// step) one number and passes it with every sample of that weather, so the renderer's frames
/// (RenderResult::weatherVersion) and the service's status count the same thing. Samples of one version
/// differ by their valid time (WindowKey). kNewWeatherVersion: one newer than any the renderer was given.
inline constexpr uint64_t kNewWeatherVersion = 0;

/// Replaces the weather (copied). Takes effect at the next renderView, which makes its window on the
/// frame path (for one-shot renders and tests). Forgets a staged weather.
void setWeather(Renderer& r, const WeatherSnapshot& snapshot, uint64_t version = kNewWeatherVersion);

/// Stages a new weather (weather_stage.h): its snapshot is made by `make` (or given), validated and its
/// window prepared on a worker thread while frames keep drawing the current weather; the first frame
/// after that (and after releaseStagedWeather with StageSwap::WhenReleased) draws it and drops the
/// reprojection history (with StageHistory::Keep, a small step such as a fade step, it keeps it). A newer
/// stage replaces one not swapped in yet; a bad weather is dropped (the current one stays;
/// weather.stage.lastError says why). With no weather drawn yet, the next frame waits for it. Returns the
/// version the weather will have (RenderResult::weatherVersion): `version`, or a new one.
uint64_t stageWeather(Renderer& r, WeatherMaker make, StageSwap swap = StageSwap::WhenReady,
                      StageHistory history = StageHistory::Drop, uint64_t version = kNewWeatherVersion);
uint64_t stageWeather(Renderer& r, std::shared_ptr<const WeatherSnapshot> snapshot,
                      StageSwap swap = StageSwap::WhenReady, StageHistory history = StageHistory::Drop,
                      uint64_t version = kNewWeatherVersion);
/// Lets a weather staged with StageSwap::WhenReleased swap in at the first frame it is ready for.
void releaseStagedWeather(Renderer& r);
/// Forgets the staged weather (a job under way finishes on the worker; its result is dropped).
void cancelStagedWeather(Renderer& r);
/// True from stageWeather until the weather swapped in, was refused or cancelled.
bool weatherStagePending(const Renderer& r);

/// Forgets the reprojection history: the next reprojected frame uses fresh pixels only (teleport,
/// weather swap, time jump). setWeather does this too; large moves, turns and time jumps do it
/// automatically (limits in reprojection.h). Counted in reconstruct.reprojection.drops.
void dropHistory(Renderer& r);

/// Renders one view and reads back the images request.readback asks for: submitView then finishView. With
/// quality.reprojected the cloud image is reconstructed from this frame's 1/16 of marched pixels and the
/// previous reprojected frame; full renders in between do not disturb that history. With
/// quality.accumulationFrames > 1 (and not reprojected) the frames are averaged on the host.
SkyStatus renderView(Renderer& r, const ViewRequest& request, const QualitySettings& quality, RenderResult& result);

/// Prepares one frame on the CPU, records it and submits it, without waiting for the GPU: a caller can
/// prepare the next frame while the GPU runs this one. At most kFramesInFlight tickets may be pending;
/// collect them with finishView in the order they were submitted. One frame: accumulationFrames is ignored.
/// `request` must have passed validateView (view_validation.h): the service checks each view where it
/// enters and this does not check it again; renderView does, for callers that draw directly.
SkyStatus submitView(Renderer& r, const ViewRequest& request, const QualitySettings& quality, FrameTicket& ticket);
/// Waits for the ticket's frame and fills `result` (GPU times, facts, and with `copyPixels` the pixels asked
/// for; without, the pixel vectors are left empty and mappedFrame gives them in place). `result`'s vectors
/// keep their capacity from frame to frame.
SkyStatus finishView(Renderer& r, FrameTicket& ticket, RenderResult& result, bool copyPixels = true);

/// A finished frame's pixels where the GPU copied them (the frame context's host-cached readback buffer):
/// valid until that context records again, kFramesInFlight submitView calls later. Null: not read back.
struct MappedFrame
{
    const uint8_t* displayRgba8 = nullptr;
    const uint16_t* skyRgbaHalf = nullptr;
    const uint16_t* cloudLayerRgbaHalf = nullptr;
    const float* cloudDepthM = nullptr;
    const float* depthLayerM = nullptr;  ///< two floats a pixel (RenderResult::depthLayerM)
    const float* shadowTransmittance = nullptr;
};
MappedFrame mappedFrame(const Renderer& r, const FrameTicket& ticket);
/// Why the last reprojected frame did not use history ("" when it did).
const std::string& lastHistoryDropReason(const Renderer& r);

}  // namespace sky
