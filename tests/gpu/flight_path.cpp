// SPDX-License-Identifier: MIT
#include "tests/gpu/flight_path.h"

#include "tests/gpu/image_compare.h"
#include "tests/gpu/scenes.h"
#include "tests/gpu/sharpness.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sky::testscenes
{
namespace
{

constexpr double kFrameS = 1.0 / 60.0;

RenderResult renderChecked(Renderer& r, const ViewRequest& view, const QualitySettings& q)
{
    RenderResult result;
    SkyStatus s = renderView(r, view, q, result);
    EXPECT_TRUE(s.ok()) << s.message;
    return result;
}

}  // namespace

void stepPose(ViewRequest& view, const Motion& motion)
{
    CameraFrame cam = computeCameraFrame(view.pose);
    double h = view.pose.headingDeg * M_PI / 180.0, d = motion.speedMS * kFrameS;
    view.pose.latDeg += d * std::cos(h) / cam.meridionalRadiusM * 180.0 / M_PI;
    view.pose.lonDeg +=
        d * std::sin(h) / (cam.primeVerticalRadiusM * std::cos(view.pose.latDeg * M_PI / 180.0)) * 180.0 / M_PI;
    view.pose.altitudeM += motion.climbMS * kFrameS;
    view.pose.pitchDeg += motion.pitchDegPerS * kFrameS;
    view.pose.headingDeg = std::fmod(view.pose.headingDeg + motion.turnDegPerS * kFrameS + 360.0, 360.0);
}

FlightStats flySegment(Renderer& r, ViewRequest& view, const Motion& motion, int warmFrames, int measuredFrames,
                       const std::string& name, const std::string& pngPath)
{
    QualitySettings full = testQuality(), reprojected = reprojectedQuality();
    FlightStats stats;
    for (int k = 0; k < warmFrames; ++k)
    {
        stepPose(view, motion);
        renderChecked(r, view, reprojected);
    }
    uint32_t w = view.width, h = view.height;
    std::vector<ColumnBand> edges;
    if (motion.pitchDegPerS > 0.0)
        edges.push_back({0, w, 0, kEdgeBandPx});
    else if (motion.pitchDegPerS < 0.0)
        edges.push_back({0, w, h - kEdgeBandPx, h});
    else
    {
        if (motion.turnDegPerS >= 0.0)
            edges.push_back({w - kEdgeBandPx, w});
        if (motion.turnDegPerS <= 0.0)
            edges.push_back({0, kEdgeBandPx});
    }
    RenderResult frame, reference, previousReference;
    ViewRequest previousView;
    for (int k = 0; k < measuredFrames; ++k)
    {
        stepPose(view, motion);
        frame = renderChecked(r, view, reprojected);
        bool dropped = !lastHistoryDropReason(r).empty();
        reference = renderChecked(r, view, full);
        double pc = psnrCloud(frame, reference), pd = psnrDisplay(frame, reference);
        double edgeDb = 1e9, edgeAbs = 0.0, edgeSharpness = 1e9;
        for (ColumnBand b : edges)
        {
            edgeDb = std::min(edgeDb, psnrCloud(frame, reference, b));
            edgeAbs = std::max(edgeAbs, meanAbsCloudError(frame, reference, b));
            edgeSharpness = std::min(edgeSharpness, sharpnessRatio(frame, reference, b));
        }
        const double sharpness = sharpnessRatio(frame, reference);
        double self = k > 0 ? psnrResampled(resampleCloud(previousReference, previousView, view), reference) : 0.0;
        std::printf("%s frame %d: alt %.0f m, block %u, cloud PSNR %.1f dB, display %.1f dB, edge cloud %.1f dB "
                    "(mean abs %.4f), sharpness %.3f (edge %.3f) of the full render's, reference vs previous "
                    "%.1f dB%s\n",
                    name.c_str(), k + 1, view.pose.altitudeM, frame.marchBlockPx, pc, pd, edgeDb, edgeAbs, sharpness,
                    edgeSharpness, self,
                    dropped ? (", history dropped: " + lastHistoryDropReason(r)).c_str() : "");
        if (k > 0)
            stats.worstReferenceDb = std::min(stats.worstReferenceDb, self);
        stats.worstEdgeDeficitDb = std::max(stats.worstEdgeDeficitDb, pc - edgeDb);
        stats.lastBlockPx = frame.marchBlockPx;
        stats.lastBlockReason = frame.marchBlockReason;
        stats.minBlockPx = std::min(stats.minBlockPx, frame.marchBlockPx);
        stats.maxBlockPx = std::max(stats.maxBlockPx, frame.marchBlockPx);
        if (frame.marchBlockPx == 1 && frame.cloudRgbaHalf != reference.cloudRgbaHalf)
            ++stats.fullBlockFramesNotExact;
        previousReference = reference;
        previousView = view;
        stats.worstCloudDb = std::min(stats.worstCloudDb, pc);
        stats.worstDisplayDb = std::min(stats.worstDisplayDb, pd);
        stats.worstEdgeCloudDb = std::min(stats.worstEdgeCloudDb, edgeDb);
        stats.worstEdgeMeanAbs = std::max(stats.worstEdgeMeanAbs, edgeAbs);
        stats.lowestSharpness = std::min(stats.lowestSharpness, sharpness);
        stats.lowestEdgeSharpness = std::min(stats.lowestEdgeSharpness, edgeSharpness);
        stats.historyDrops += dropped ? 1 : 0;
        ++stats.frames;
    }
    if (!pngPath.empty())
    {
        writeDisplayPng(frame, pngPath);
        writeDisplayPng(reference, pngPath.substr(0, pngPath.size() - 4) + "-full.png");
    }
    return stats;
}

}  // namespace sky::testscenes
