// SPDX-License-Identifier: MIT
#include "weather_ingest/wrf_mapping.h"

#include "weather_ingest/civil_time.h"
#include "weather_ingest/curvilinear_resampler.h"
#include "weather_ingest/ingest_error.h"
#include "weather_ingest/pressure_altitude.h"
#include "weather_ingest/regular_grid.h"
#include "weather_ingest/snapshot_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

namespace sky
{
namespace
{

constexpr double kG = 9.81;                 // m s^-2, the value WRF itself uses (share/module_model_constants.F)
constexpr double kRd = 287.0;               // J kg^-1 K^-1, WRF's r_d
constexpr double kRdOverCp = 287.0 / 1004.5;  // WRF's rcp (r_d / cp)
constexpr double kTheta0K = 300.0;          // WRF's base potential temperature t0 (T is theta - 300 K)
constexpr double kP0Pa = 100000.0;          // reference pressure of potential temperature
constexpr float kCloudyMixingRatio = 1e-5f; // kg/kg: a common cloud threshold for model output (0.01 g/kg)
constexpr double kWaterPathScaleKgM2 = 0.02;  // W at which coverage reaches 63 %: 20 g m^-2 is optical depth ~3
constexpr double kLowTopM = 2000.0;         // WMO étages at mid-latitudes (Cloud Atlas): low < 2 km
constexpr double kMiddleTopM = 6000.0;      // middle 2-7 km, high from 5 km: the split is put at 6 km
constexpr double kDeepBaseBelowM = 3000.0;  // convective run: base below 3 km ...
constexpr double kDeepMinDepthM = 5000.0;   // ... and at least 5 km deep (cumulonimbus scale)

/// Per-column results for one band (low, middle, convective, high).
struct BandColumns
{
    std::vector<float> coverage, baseM, topM, windU, windV;
    void resize(size_t n)
    {
        coverage.assign(n, 0.0f);
        baseM.assign(n, NAN);
        topM.assign(n, NAN);
        windU.assign(n, 0.0f);
        windV.assign(n, 0.0f);
    }
};

struct WrfDims
{
    size_t nt = 0, nz = 0, ny = 0, nx = 0;
};

WrfDims checkDims(const NcFile& f)
{
    const NcFile::Variable q = f.variable("QCLOUD");
    if (q.shape.size() != 4)
        throw IngestError(IngestErrorKind::Corrupt, f.path(), "variable QCLOUD", "", "expected (Time, bottom_top, south_north, west_east)");
    WrfDims d{q.shape[0], q.shape[1], q.shape[2], q.shape[3]};
    if (d.nt == 0 || d.nt > kMaxSnapshotsPerFile || d.nz == 0 || d.nz > 500 || d.ny < 2 || d.nx < 2 ||
        double(d.ny) * double(d.nx) > double(kMaxSnapshotCells))
        throw IngestError(IngestErrorKind::TooLarge, f.path(), "variable QCLOUD", "",
                          "dimensions " + std::to_string(d.nt) + " x " + std::to_string(d.nz) + " x " +
                              std::to_string(d.ny) + " x " + std::to_string(d.nx) + " are empty or absurd");
    const auto expect = [&](const char* name, std::vector<size_t> shape) {
        if (!f.hasVariable(name))
            return;
        const NcFile::Variable v = f.variable(name);
        if (v.shape != shape)
            throw IngestError(IngestErrorKind::Corrupt, f.path(), std::string("variable ") + name, "",
                              "dimensions do not match QCLOUD's (staggering?)");
    };
    expect("PH", {d.nt, d.nz + 1, d.ny, d.nx});
    expect("PHB", {d.nt, d.nz + 1, d.ny, d.nx});
    for (const char* v : {"QICE", "QRAIN", "P", "PB", "T"})
        expect(v, {d.nt, d.nz, d.ny, d.nx});
    expect("U", {d.nt, d.nz, d.ny, d.nx + 1});
    expect("V", {d.nt, d.nz, d.ny + 1, d.nx});
    for (const char* v : {"RAINC", "RAINNC", "RAINSH", "COSALPHA", "SINALPHA"})
        expect(v, {d.nt, d.ny, d.nx});
    return d;
}

class WrfReader
{
public:
    WrfReader(const NcFile& f, const WrfDims& d) : f_(f), d_(d) {}

    /// A 3D (or 2D when nz == 0) slab of one time, or empty when the variable is absent.
    std::vector<float> slab(const char* name, size_t t, size_t nz, size_t ny, size_t nx) const
    {
        if (!f_.hasVariable(name))
            return {};
        if (nz == 0)
            return f_.readFloat(name, {t, 0, 0}, {1, ny, nx});
        return f_.readFloat(name, {t, 0, 0, 0}, {1, nz, ny, nx});
    }

    /// Coordinates: XLAT/XLONG of time 0, as (Time, y, x) or (y, x).
    std::vector<float> coordinate(const char* name) const
    {
        const NcFile::Variable v = f_.variable(name);
        if (v.shape.size() == 3 && v.shape[1] == d_.ny && v.shape[2] == d_.nx)
            return f_.readFloat(name, {0, 0, 0}, {1, d_.ny, d_.nx});
        if (v.shape.size() == 2 && v.shape[0] == d_.ny && v.shape[1] == d_.nx)
            return f_.readFloat(name, {0, 0}, {d_.ny, d_.nx});
        throw IngestError(IngestErrorKind::Corrupt, f_.path(), std::string("variable ") + name, "",
                          "dimensions do not match QCLOUD's horizontal grid");
    }

private:
    const NcFile& f_;
    const WrfDims& d_;
};

/// Rotation from grid-relative to earth-relative winds: (cos, sin) per column, or empty for none.
void windRotation(const NcFile& f, const WrfReader& r, const WrfDims& d, const std::vector<float>& lon,
                  std::vector<float>& cosA, std::vector<float>& sinA)
{
    if (f.hasVariable("COSALPHA") && f.hasVariable("SINALPHA"))
    {
        cosA = r.slab("COSALPHA", 0, 0, d.ny, d.nx);
        sinA = r.slab("SINALPHA", 0, 0, d.ny, d.nx);
        return;
    }
    // No COSALPHA/SINALPHA (older WRF): the projection's cone factor gives the angle between grid north
    // and true north, alpha = cone * (lon - STAND_LON) (Lambert conformal: Snyder 1987, eq. 15-3).
    const int proj = int(f.globalNumber("MAP_PROJ").value_or(0));
    const double tl1 = f.globalNumber("TRUELAT1").value_or(0) * std::numbers::pi / 180;
    const double tl2 = f.globalNumber("TRUELAT2").value_or(0) * std::numbers::pi / 180;
    double cone = 0;
    if (proj == 1)
        cone = std::abs(tl1 - tl2) > 1e-3 ? (std::log(std::cos(tl1)) - std::log(std::cos(tl2))) /
                                                (std::log(std::tan(std::numbers::pi / 4 - std::abs(tl1) / 2)) -
                                                 std::log(std::tan(std::numbers::pi / 4 - std::abs(tl2) / 2)))
                                          : std::sin(std::abs(tl1));
    else if (proj == 2)
        cone = 1;
    if (cone == 0)
        return;
    const double standLon = f.globalNumber("STAND_LON").value_or(0);
    const double hemisphere = tl1 < 0 ? -1.0 : 1.0;
    cosA.resize(lon.size());
    sinA.resize(lon.size());
    for (size_t i = 0; i < lon.size(); ++i)
    {
        const double alpha = wrapLongitudeDeg(double(lon[i]) - standLon) * cone * hemisphere * std::numbers::pi / 180;
        cosA[i] = float(std::cos(alpha));
        sinA[i] = float(-std::sin(alpha));  // COSALPHA/SINALPHA convention: u_earth = u cos - v sin
    }
}

/// Precipitation rate (mm/h) at each time from an accumulation (mm) by centred differences.
std::vector<std::vector<float>> ratesFromAccumulation(const std::vector<std::vector<float>>& acc,
                                                      const std::vector<int64_t>& timesS)
{
    const size_t nt = acc.size();
    std::vector<std::vector<float>> rates(nt);
    if (nt < 2)
        return rates;
    for (size_t t = 0; t < nt; ++t)
    {
        const size_t a = t == 0 ? 0 : t - 1;
        const size_t b = t + 1 == nt ? t : t + 1;
        const double hours = double(timesS[b] - timesS[a]) / 3600.0;
        rates[t].resize(acc[t].size());
        for (size_t i = 0; i < acc[t].size(); ++i)
            rates[t][i] = hours > 0 ? float(std::max(0.0, double(acc[b][i] - acc[a][i]) / hours)) : 0.0f;
    }
    return rates;
}

/// Throws MissingFields naming the WRF variables that are absent.
void requireWrfVariables(const NcFile& f)
{
    std::vector<std::string> missing;
    for (const char* v : kWrfRequired)
        if (!f.hasVariable(v))
            missing.push_back(v);
    if (missing.empty())
        return;
    std::string list;
    for (const std::string& m : missing)
        list += (list.empty() ? "" : ", ") + m;
    const bool none = missing.size() == std::size(kWrfRequired);
    throw IngestError(IngestErrorKind::MissingFields, f.path(), "", "",
                      none ? "none of the variables of WRF output (Times, XLAT, XLONG, PH, PHB, QCLOUD) or of a "
                             "supported model were found"
                           : "WRF variables missing: " + list);
}

/// Unix times (s) of the WRF Times strings, one per QCLOUD time.
std::vector<int64_t> wrfTimes(const NcFile& f, const WrfDims& d, const std::vector<std::string>& timeTexts)
{
    if (timeTexts.size() != d.nt)
        throw IngestError(IngestErrorKind::Corrupt, f.path(), "variable Times", "", "one time per QCLOUD time needed");
    std::vector<int64_t> times(d.nt);
    for (size_t t = 0; t < d.nt; ++t)
        if (!parseWrfTime(timeTexts[t], times[t]))
            throw IngestError(IngestErrorKind::Corrupt, f.path(), "variable Times", "",
                              "'" + timeTexts[t] + "' is not a time like 2005-08-28_12:00:00");
    return times;
}

/// The resampler from XLAT/XLONG onto a regular grid; bad coordinates are BadValues.
std::unique_ptr<CurvilinearResampler> makeResampler(const NcFile& f, const WrfDims& d, const std::vector<float>& lat,
                                                    const std::vector<float>& lon)
{
    try
    {
        return std::make_unique<CurvilinearResampler>(lat, lon, d.ny, d.nx, kMaxSnapshotCells);
    }
    catch (const std::exception& e)
    {
        throw IngestError(IngestErrorKind::BadValues, f.path(), "variable XLAT/XLONG", "", e.what());
    }
}

/// Precipitation rates (mm/h) per time and column, convective (RAINC + RAINSH) and large-scale (RAINNC).
struct PrecipitationRates
{
    std::vector<std::vector<float>> convective, largeScale;
};

PrecipitationRates precipitationRates(const NcFile& f, const WrfReader& r, const WrfDims& d,
                                      const std::vector<int64_t>& times, const ValueChecker& check)
{
    const size_t cols = d.ny * d.nx;
    std::vector<std::vector<float>> accConv(d.nt), accLarge(d.nt);
    const bool haveRain = f.hasVariable("RAINC") || f.hasVariable("RAINNC");
    for (size_t t = 0; t < d.nt && haveRain; ++t)
    {
        accConv[t].assign(cols, 0.0f);
        accLarge[t].assign(cols, 0.0f);
        for (const char* v : {"RAINC", "RAINSH"})
            if (f.hasVariable(v))
            {
                const std::vector<float> a = r.slab(v, t, 0, d.ny, d.nx);
                for (size_t i = 0; i < cols; ++i)
                    accConv[t][i] += std::isfinite(a[i]) ? a[i] : 0.0f;
            }
        if (f.hasVariable("RAINNC"))
            accLarge[t] = r.slab("RAINNC", t, 0, d.ny, d.nx);
    }
    PrecipitationRates rates{ratesFromAccumulation(accConv, times), ratesFromAccumulation(accLarge, times)};
    if (haveRain && d.nt < 2)
        check.warn("one time only: precipitation rates cannot be derived from RAINC/RAINNC, set to 0");
    return rates;
}

/// The 3D fields of one time; optional ones are empty when absent.
struct WrfLevels
{
    std::vector<float> qc, qi, qr;  ///< mixing ratios (kg/kg): cloud water, ice, rain
    std::vector<float> heightM;     ///< (PH + PHB) / g on the staggered (nz + 1) levels
    std::vector<float> pp, pb, th;  ///< pressure perturbation and base (Pa), theta - 300 K
    std::vector<float> u, v;        ///< grid-relative winds on the staggered columns (m/s)
};

WrfLevels readLevels(const WrfReader& r, const WrfDims& d, size_t t, const ValueChecker& check, const std::string& base)
{
    WrfLevels l;
    l.qc = r.slab("QCLOUD", t, d.nz, d.ny, d.nx);
    l.qi = r.slab("QICE", t, d.nz, d.ny, d.nx);
    l.qr = r.slab("QRAIN", t, d.nz, d.ny, d.nx);
    l.heightM = r.slab("PH", t, d.nz + 1, d.ny, d.nx);
    const std::vector<float> phb = r.slab("PHB", t, d.nz + 1, d.ny, d.nx);
    l.pp = r.slab("P", t, d.nz, d.ny, d.nx);
    l.pb = r.slab("PB", t, d.nz, d.ny, d.nx);
    l.th = r.slab("T", t, d.nz, d.ny, d.nx);
    l.u = r.slab("U", t, d.nz, d.ny, d.nx + 1);
    l.v = r.slab("V", t, d.nz, d.ny + 1, d.nx);
    std::vector<float>& ph = l.heightM;
    for (size_t i = 0; i < ph.size(); ++i)
        ph[i] = float((double(ph[i]) + double(phb[i])) / kG);  // geopotential -> height (m)
    // Index space as a pseudo-grid: messages then name (level * rows + row, column).
    const LatLonGrid levelGrid{0, 0, 1, 1, uint32_t(ph.size() / d.nx), uint32_t(d.nx)};
    check.range(ph, -1000.0f, 100000.0f, "PH+PHB", base + " variable PH/PHB", levelGrid);
    return l;
}

/// The four bands' columns (low, middle, convective, high) and their running sums.
struct BandSums
{
    BandColumns bands[4];
    std::vector<float> waterPath[4];  ///< kg m^-2
    std::vector<float> windCount[4];  ///< levels whose wind was added

    explicit BandSums(size_t cols)
    {
        for (BandColumns& b : bands)
            b.resize(cols);
        for (size_t k = 0; k < 4; ++k)
        {
            waterPath[k].assign(cols, 0.0f);
            windCount[k].assign(cols, 0.0f);
        }
    }
};

/// Rotation from grid-relative to earth-relative winds, per column (empty: none).
struct WindRotation
{
    std::vector<float> cosA, sinA;
};

/// Adds level kk of column c (row j, column i) to its band: water path, base, top and earth-relative wind.
void addCloudyLevel(const WrfLevels& l, const WrfDims& d, const WindRotation& rot, size_t c, size_t kk, bool deep,
                    BandSums& sums)
{
    const size_t cols = d.ny * d.nx;
    const size_t j = c / d.nx, i = c % d.nx;
    const auto at = [&](size_t k) { return k * cols + c; };
    const double zBot = l.heightM[at(kk)], zTop = l.heightM[at(kk + 1)], zMid = 0.5 * (zBot + zTop);
    const size_t band = deep ? 2 : zMid < kLowTopM ? 0 : zMid < kMiddleTopM ? 1 : 3;
    double pPa = standardAtmospherePressurePa(zMid), tK = 0;
    if (!l.pp.empty() && !l.pb.empty())
        pPa = double(l.pp[at(kk)]) + double(l.pb[at(kk)]);
    tK = l.th.empty() ? 288.15 - 0.0065 * std::min(zMid, 11000.0)
                      : (double(l.th[at(kk)]) + kTheta0K) * std::pow(pPa / kP0Pa, kRdOverCp);
    const double rho = pPa / (kRd * tK);
    const double q = double(l.qc[at(kk)]) + (l.qi.empty() ? 0.0 : double(l.qi[at(kk)])) +
                     (l.qr.empty() || !std::isfinite(l.qr[at(kk)]) ? 0.0 : double(l.qr[at(kk)]));
    sums.waterPath[band][c] += float(rho * q * (zTop - zBot));
    BandColumns& b = sums.bands[band];
    b.baseM[c] = std::isnan(b.baseM[c]) ? float(zBot) : std::min(b.baseM[c], float(zBot));
    b.topM[c] = std::isnan(b.topM[c]) ? float(zTop) : std::max(b.topM[c], float(zTop));
    if (!l.u.empty() && !l.v.empty())
    {
        const std::vector<float>& u = l.u;
        const std::vector<float>& v = l.v;
        const float ug = 0.5f * (u[(kk * d.ny + j) * (d.nx + 1) + i] + u[(kk * d.ny + j) * (d.nx + 1) + i + 1]);
        const float vg = 0.5f * (v[(kk * (d.ny + 1) + j) * d.nx + i] + v[(kk * (d.ny + 1) + j + 1) * d.nx + i]);
        const float ca = rot.cosA.empty() ? 1.0f : rot.cosA[c], sa = rot.sinA.empty() ? 0.0f : rot.sinA[c];
        b.windU[c] += ug * ca - vg * sa;
        b.windV[c] += vg * ca + ug * sa;
        sums.windCount[band][c] += 1.0f;
    }
}

/// Walks column c's runs of cloudy levels (a run deep enough from low enough is convective), then turns
/// each band's water path into coverage and its wind sum into a mean.
void integrateColumn(const WrfLevels& l, const WrfDims& d, const WindRotation& rot, size_t c, BandSums& sums)
{
    const size_t cols = d.ny * d.nx;
    const auto at = [&](size_t k) { return k * cols + c; };
    const auto cond = [&](size_t kk) {
        const float q = l.qc[at(kk)] + (l.qi.empty() ? 0.0f : l.qi[at(kk)]);
        return std::isfinite(q) && q >= kCloudyMixingRatio;
    };
    size_t k = 0;
    while (k < d.nz)
    {
        if (!cond(k))
        {
            ++k;
            continue;
        }
        size_t end = k;
        while (end + 1 < d.nz && cond(end + 1))
            ++end;
        const double runBase = l.heightM[at(k)], runTop = l.heightM[at(end + 1)];
        const bool deep = runBase < kDeepBaseBelowM && runTop - runBase >= kDeepMinDepthM;
        for (size_t kk = k; kk <= end; ++kk)
            addCloudyLevel(l, d, rot, c, kk, deep, sums);
        k = end + 1;
    }
    for (size_t band = 0; band < 4; ++band)
    {
        BandColumns& b = sums.bands[band];
        b.coverage[c] = float(1.0 - std::exp(-double(sums.waterPath[band][c]) / kWaterPathScaleKgM2));
        if (sums.windCount[band][c] > 0)
        {
            b.windU[c] /= sums.windCount[band][c];
            b.windV[c] /= sums.windCount[band][c];
        }
    }
}

std::vector<float> zeroNan(std::vector<float> x)
{
    for (float& e : x)
        e = std::isfinite(e) ? e : 0.0f;
    return x;
}

/// What the snapshot of one time is assembled from.
struct WrfTimeInputs
{
    const CurvilinearResampler& resampler;
    const BandColumns* bands;  ///< low, middle, convective, high
    int64_t validTimeUnixS;
    const std::string& timeText;
    const std::string& base;  ///< the file's name, for provenance
    const std::vector<float>& convRate;
    const std::vector<float>& largeRate;
    bool haveWind;
};

/// The three volumetric layers (low, middle, convective) resampled, checked and attributed.
void resampleLayers(const WrfTimeInputs& in, const ValueChecker& check, WeatherSnapshot& s)
{
    const CurvilinearResampler& resampler = in.resampler;
    for (size_t li = 0; li < 3; ++li)
    {
        CloudLayerFields& l = s.layers[li];
        l.coverage = resampler.resample(in.bands[li].coverage);
        l.baseAltitudeM = resampler.resample(in.bands[li].baseM);
        l.topAltitudeM = resampler.resample(in.bands[li].topM);
        l.windEastMS = zeroNan(resampler.resample(in.bands[li].windU));
        l.windNorthMS = zeroNan(resampler.resample(in.bands[li].windV));
        check.baseBelowTop(l.baseAltitudeM, l.topAltitudeM, l.name + " base vs top", in.base, s.grid);
        const std::string p = "layers/" + std::to_string(li) + "/";
        s.provenance[p + "coverage"] = in.base + " QCLOUD+QICE+QRAIN water path, time " + in.timeText;
        s.provenance[p + "baseAltitudeM"] = in.base + " PH+PHB at the lowest cloudy level";
        s.provenance[p + "topAltitudeM"] = in.base + " PH+PHB at the highest cloudy level";
    }
}

WeatherSnapshot snapshotOfTime(const WrfTimeInputs& in, const ValueChecker& check)
{
    const CurvilinearResampler& resampler = in.resampler;
    WeatherSnapshot s;
    s.grid = resampler.grid();
    s.validTimeUnixS = in.validTimeUnixS;
    const size_t n = s.grid.cellCount();
    s.layers = makeEmptyLayers(n);
    resampleLayers(in, check, s);
    const BandColumns& high = in.bands[3];
    s.high.coverage = resampler.resample(high.coverage);
    s.high.altitudeM.resize(n);
    const std::vector<float> hb = resampler.resample(high.baseM), ht = resampler.resample(high.topM);
    for (size_t i = 0; i < n; ++i)
        s.high.altitudeM[i] = 0.5f * (hb[i] + ht[i]);
    s.high.windEastMS = zeroNan(resampler.resample(high.windU));
    s.high.windNorthMS = zeroNan(resampler.resample(high.windV));
    s.provenance["high/coverage"] = in.base + " water path of cloudy levels above 6 km";
    std::vector<float> conv, large;
    if (!in.convRate.empty())
    {
        conv = zeroNan(resampler.resample(in.convRate));
        large = zeroNan(resampler.resample(in.largeRate));
    }
    attributePrecipitation(s, conv, large);
    s.provenance["precipitation/convective"] = conv.empty() ? "absent" : in.base + " d(RAINC+RAINSH)/dt";
    s.provenance["precipitation/largeScale"] = large.empty() ? "absent" : in.base + " d(RAINNC)/dt";
    s.provenance["wind"] = !in.haveWind ? "absent: 0 m/s" : in.base + " U/V de-staggered, earth-relative";
    s.provenance["grid"] = in.base + " XLAT/XLONG resampled to a regular grid (" +
                           std::to_string(int(resampler.coveredFraction() * 100)) + " % inside the domain)";
    assignCloudTypes(s, conv);
    s.provenance["types"] = "cloud-type rule table (README \"Cloud types\")";
    return s;
}

}  // namespace

bool parseWrfTime(const std::string& text, int64_t& unixS)
{
    int y = 0, mo = 0, d = 0, h = 0, mi = 0, s = 0;
    char sep = 0;
    if (std::sscanf(text.c_str(), "%4d-%2d-%2d%c%2d:%2d:%2d", &y, &mo, &d, &sep, &h, &mi, &s) != 7 ||
        (sep != '_' && sep != 'T' && sep != ' ') || mo < 1 || mo > 12 || d < 1 || d > 31 || h > 23 || mi > 59 ||
        s > 60)
        return false;
    unixS = unixTimeFromCivil(y, mo, d, h, mi, s);
    return true;
}

std::vector<WeatherSnapshot> mapWrfFile(const NcFile& f, const MappingOptions& options,
                                        std::vector<std::string>& warnings, const ProgressFn& progress)
{
    requireWrfVariables(f);
    const WrfDims d = checkDims(f);
    const WrfReader r(f, d);
    const size_t cols = d.ny * d.nx;
    const std::string base = std::filesystem::path(f.path()).filename().string();
    const ValueChecker check(options, warnings, f.path());

    const std::vector<std::string> timeTexts = f.readStrings("Times");
    const std::vector<int64_t> times = wrfTimes(f, d, timeTexts);
    const std::vector<float> lat = r.coordinate("XLAT");
    const std::vector<float> lon = r.coordinate("XLONG");
    const std::unique_ptr<CurvilinearResampler> resampler = makeResampler(f, d, lat, lon);
    WindRotation rotation;
    windRotation(f, r, d, lon, rotation.cosA, rotation.sinA);
    const PrecipitationRates rates = precipitationRates(f, r, d, times, check);

    std::vector<WeatherSnapshot> out;
    for (size_t t = 0; t < d.nt; ++t)
    {
        if (progress)
            progress(double(t) / double(d.nt), "WRF time " + timeTexts[t]);
        const WrfLevels levels = readLevels(r, d, t, check, base);
        BandSums sums(cols);
        for (size_t c = 0; c < cols; ++c)
            integrateColumn(levels, d, rotation, c, sums);
        const WrfTimeInputs inputs{*resampler,         sums.bands,           times[t],          timeTexts[t], base,
                                   rates.convective[t], rates.largeScale[t], !levels.u.empty()};
        out.push_back(snapshotOfTime(inputs, check));
    }
    if (progress)
        progress(1.0, "WRF done");
    return out;
}

}  // namespace sky
