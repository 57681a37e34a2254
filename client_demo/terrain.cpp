// SPDX-License-Identifier: MIT
#include "client_demo/terrain.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace demo
{
namespace
{

constexpr double kDegToRad = M_PI / 180.0;

// Below this height a peak's tail is taken as 0 (m): the flat ground there is met analytically.
constexpr double kNegligibleHeightM = 0.1;
// Ray-march limits: the shortest step (m, so that a ray grazing a slope still advances) and the most steps
// per ray (a ray skimming a ridge for kilometres; past it the flat ground is taken).
constexpr double kMinStepM = 0.5;
constexpr int kMaxSteps = 600;

double smoothstep(double e0, double e1, double x)
{
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

glm::dvec3 mix(const glm::dvec3& a, const glm::dvec3& b, double w) { return a * (1.0 - w) + b * w; }

// East/north of (latDeg, lonDeg) from the camera's eye in its tangent plane (the inverse of groundLatLonDeg).
std::array<double, 2> offsetFromEyeM(const GroundCamera& camera, double latDeg, double lonDeg)
{
    SkyShmShadowGeoRef atEye{};
    atEye.centre_lat_deg = camera.latDeg;
    atEye.centre_lon_deg = camera.lonDeg;
    return offsetFromShadowCentreM(latDeg, lonDeg, atEye);
}

// The stretch [tNear, tFar] of the ray whose horizontal track passes within some peak's reach.
bool peakInterval(const LocalTerrain& terrain, const glm::dvec3& dir, double& tNear, double& tFar)
{
    tNear = INFINITY;
    tFar = -INFINITY;
    const double a = dir.x * dir.x + dir.y * dir.y;
    for (const LocalTerrain::Peak& p : terrain.peaks)
    {
        const double c = p.eastM * p.eastM + p.northM * p.northM - p.reachM * p.reachM;
        if (a < 1e-12)
        {
            // Straight up or down: the whole ray when the eye is within reach.
            if (c <= 0.0)
                tNear = 0.0, tFar = INFINITY;
            continue;
        }
        const double halfB = -(dir.x * p.eastM + dir.y * p.northM);
        const double disc = halfB * halfB - a * c;
        if (disc < 0.0)
            continue;
        const double root = std::sqrt(disc);
        tNear = std::min(tNear, (-halfB - root) / a);
        tFar = std::max(tFar, (-halfB + root) / a);
    }
    tNear = std::max(tNear, 0.0);
    return tFar > tNear;
}

void fillHit(const LocalTerrain& terrain, const glm::dvec3& dir, double t, TerrainHit& hit)
{
    hit.distanceM = t;
    hit.eastM = t * dir.x;
    hit.northM = t * dir.y;
    std::array<double, 2> grad{0.0, 0.0};
    hit.heightM = terrainHeightM(terrain, hit.eastM, hit.northM, &grad);
    hit.normalEnu = glm::normalize(glm::dvec3(-grad[0], -grad[1], 1.0));
}

}  // namespace

double rayHeightM(const GroundCamera& camera, const glm::dvec3& dir, double t)
{
    // |e + t d - c| - R with the sphere's centre c straight below the eye.
    const double rPlusH = camera.earthRadiusM + camera.altitudeM;
    const glm::dvec3 p(t * dir.x, t * dir.y, rPlusH + t * dir.z);
    return glm::length(p) - camera.earthRadiusM;
}

DemoTerrain demoMountainAhead(double latDeg, double lonDeg, double headingDeg)
{
    GroundCamera start;
    start.latDeg = latDeg;
    start.lonDeg = lonDeg;
    const double h = headingDeg * kDegToRad;
    const glm::dvec3 ahead(std::sin(h), std::cos(h), 0.0);
    const glm::dvec3 right(std::cos(h), -std::sin(h), 0.0);
    auto place = [&](const glm::dvec3& offsetM, double heightM, double sigmaM) {
        GroundHit at;
        at.eastM = offsetM.x;
        at.northM = offsetM.y;
        const std::array<double, 2> latLon = groundLatLonDeg(start, at);
        return TerrainPeak{latLon[0], latLon[1], heightM, sigmaM};
    };
    DemoTerrain t;
    t.peaks.push_back(place(12000.0 * ahead, 3000.0, 2200.0));
    t.peaks.push_back(place(12000.0 * ahead + 8000.0 * right, 2200.0, 2200.0));
    return t;
}

LocalTerrain localTerrain(const DemoTerrain& terrain, const GroundCamera& camera)
{
    LocalTerrain local;
    for (const TerrainPeak& peak : terrain.peaks)
    {
        if (peak.heightM <= kNegligibleHeightM || peak.sigmaM <= 0.0)
            continue;
        LocalTerrain::Peak p;
        const std::array<double, 2> en = offsetFromEyeM(camera, peak.latDeg, peak.lonDeg);
        p.eastM = en[0];
        p.northM = en[1];
        p.heightM = peak.heightM;
        p.sigmaM = peak.sigmaM;
        p.inverseTwoSigma2 = 1.0 / (2.0 * peak.sigmaM * peak.sigmaM);
        p.reachM = peak.sigmaM * std::sqrt(2.0 * std::log(peak.heightM / kNegligibleHeightM));
        // The steepest slope of a Gaussian, at r = sigma: H / sigma * exp(-1/2).
        local.maxSlope += peak.heightM / peak.sigmaM * std::exp(-0.5);
        local.peaks.push_back(p);
    }
    return local;
}

double terrainHeightM(const LocalTerrain& t, double eastM, double northM, std::array<double, 2>* gradient)
{
    double height = 0.0;
    double gx = 0.0;
    double gy = 0.0;
    for (const LocalTerrain::Peak& p : t.peaks)
    {
        const double dx = eastM - p.eastM;
        const double dy = northM - p.northM;
        const double r2 = dx * dx + dy * dy;
        if (r2 > p.reachM * p.reachM)
            continue;
        const double h = p.heightM * std::exp(-r2 * p.inverseTwoSigma2);
        height += h;
        gx -= 2.0 * p.inverseTwoSigma2 * dx * h;
        gy -= 2.0 * p.inverseTwoSigma2 * dy * h;
    }
    if (gradient)
        *gradient = {gx, gy};
    return height;
}

double slopeBoundNear(const LocalTerrain& t, double eastM, double northM, double radiusM)
{
    double bound = 0.0;
    for (const LocalTerrain::Peak& p : t.peaks)
    {
        const double dx = eastM - p.eastM;
        const double dy = northM - p.northM;
        const double nearestM = std::sqrt(dx * dx + dy * dy) - radiusM;
        if (nearestM > p.reachM)
            continue;
        // |grad| of H exp(-r^2 / (2 sigma^2)) is H r / sigma^2 exp(...): largest at r = sigma, falling beyond.
        const double slopeScale = p.heightM * 2.0 * p.inverseTwoSigma2;
        if (nearestM <= p.sigmaM)
            bound += slopeScale * p.sigmaM * std::exp(-0.5);
        else
            bound += slopeScale * nearestM * std::exp(-nearestM * nearestM * p.inverseTwoSigma2);
    }
    return bound;
}

bool intersectTerrain(const GroundCamera& camera, const LocalTerrain& terrain, const glm::dvec3& dirEnu,
                      TerrainHit& hit)
{
    if (camera.altitudeM <= terrainHeightM(terrain, 0.0, 0.0))
        return false;  // the eye is in the rock (or under the ground): nothing sensible to draw
    GroundHit flat;
    const bool flatHit = intersectGround(camera, dirEnu, flat);
    double tNear = 0.0;
    double tFar = 0.0;
    if (peakInterval(terrain, dirEnu, tNear, tFar))
    {
        if (flatHit)
            tFar = std::min(tFar, flat.distanceM);
        // The ray's height falls at most (descent rate) per metre (the earth's curvature only lifts it; the
        // 1.001 covers the ratio of radii at the eye and at the ground); the terrain rises at most (slope
        // bound) per horizontal metre. A step of gap / (sum of both) cannot pass under the surface. The
        // global bound gives a safe step s0; the bound over a disc of 16 s0 gives s1, safe when s1 <= 16 s0
        // (else 16 s0 itself is): long steps over the flat ground far from the peaks.
        const double horizontal = std::sqrt(dirEnu.x * dirEnu.x + dirEnu.y * dirEnu.y);
        const double descent = 1.001 * std::max(0.0, -dirEnu.z) + 1e-9;
        const double globalRate = terrain.maxSlope * horizontal + descent;
        double t = tNear;
        double tPrev = t;
        for (int step = 0; step < kMaxSteps && t <= tFar; ++step)
        {
            const double gap = rayHeightM(camera, dirEnu, t) - terrainHeightM(terrain, t * dirEnu.x, t * dirEnu.y);
            if (gap <= 0.0)
            {
                // Under the surface: bisect between the last point above it and this one.
                double lo = tPrev;
                double hi = t;
                for (int i = 0; i < 24 && hi - lo > 0.01; ++i)
                {
                    const double mid = 0.5 * (lo + hi);
                    const double g = rayHeightM(camera, dirEnu, mid) -
                                     terrainHeightM(terrain, mid * dirEnu.x, mid * dirEnu.y);
                    (g > 0.0 ? lo : hi) = mid;
                }
                fillHit(terrain, dirEnu, hi, hit);
                return true;
            }
            tPrev = t;
            const double safeM = gap / globalRate;
            const double reachM = 16.0 * safeM;
            const double localM =
                gap / (slopeBoundNear(terrain, t * dirEnu.x, t * dirEnu.y, reachM * horizontal) * horizontal + descent);
            t += std::max(std::max(safeM, std::min(localM, reachM)), kMinStepM);
        }
    }
    if (!flatHit)
        return false;
    fillHit(terrain, dirEnu, flat.distanceM, hit);
    return true;
}

std::array<double, 2> shadowFootprintM(const TerrainHit& hit, const TerrainLight& light)
{
    // Low lights would send the footprint far away (and out of the map): 3 degrees at least.
    const double elevation = std::max(light.elevationDeg, 3.0) * kDegToRad;
    const double run = hit.heightM / std::tan(elevation);
    const double azimuth = light.azimuthDeg * kDegToRad;
    return {hit.eastM - run * std::sin(azimuth), hit.northM - run * std::cos(azimuth)};
}

glm::dvec3 shadeTerrainLinear(const TerrainHit& hit, double latDeg, double lonDeg, const TerrainLight& light,
                              double keyTransmittance)
{
    // Albedo. Fields of 0.02 degrees (~2 km) on the flat ground, as the display-path ground has, a per-field
    // hash varying them a little; forest on the lower slopes, rock above and on steep faces, snow on top. The
    // zone borders wander by +-150 m with a pattern fixed to the earth so that they are not contour lines.
    const auto i = int64_t(std::floor(latDeg / 0.02));
    const auto j = int64_t(std::floor(lonDeg / 0.02));
    const uint64_t hash = uint64_t(i * 73856093) ^ uint64_t(j * 19349663);
    const double vary = 0.9 + 0.2 * double(hash % 101) / 100.0;
    const glm::dvec3 field = ((i + j) & 1) != 0 ? glm::dvec3(0.106, 0.074, 0.033) : glm::dvec3(0.074, 0.147, 0.033);
    const glm::dvec3 forest(0.035, 0.060, 0.025);
    const glm::dvec3 rock(0.20, 0.18, 0.16);
    const glm::dvec3 snow(0.85, 0.87, 0.92);
    const double wander = 150.0 * std::sin(latDeg * 111000.0 / 700.0) * std::sin(lonDeg * 80000.0 / 900.0);
    const double h = hit.heightM + wander;
    const double steep = smoothstep(0.85, 0.65, hit.normalEnu.z);  // ~30..50 degree slopes
    glm::dvec3 albedo = mix(field * vary, forest, smoothstep(150.0, 500.0, h));
    albedo = mix(albedo, rock, std::max(smoothstep(1600.0, 2100.0, h), 0.7 * steep));
    albedo = mix(albedo, snow, smoothstep(2500.0, 2700.0, h) * (1.0 - steep));

    // Light on the pre-exposed scale (terrain.h): the key light by the cosine of its angle to the normal,
    // dimmed by the clouds' shadow and gone below the horizon; the sky's light by the part of the sky the
    // normal sees, its share larger when the key light is low (the exposure then follows the sky).
    const double elevation = light.elevationDeg * kDegToRad;
    const double azimuth = light.azimuthDeg * kDegToRad;
    const glm::dvec3 toLight(std::sin(azimuth) * std::cos(elevation), std::cos(azimuth) * std::cos(elevation),
                             std::sin(elevation));
    const double keyUp = smoothstep(-1.0, 3.0, light.elevationDeg);
    const double cosKey = std::max(0.0, glm::dot(hit.normalEnu, toLight));
    const double key = 1.4 * keyUp * cosKey * std::clamp(keyTransmittance, 0.0, 1.0);
    const double twilight = 1.0 - std::clamp(std::sin(elevation) * 5.0, 0.0, 1.0);
    const double sky = (0.35 + 0.85 * twilight) * (0.5 + 0.5 * hit.normalEnu.z);
    // Moonlight lies under the service's exposure floor: the picture is darker than by day.
    const double night = light.isMoon ? 0.5 : 1.0;
    return albedo * (key + sky) * night;
}

}  // namespace demo
