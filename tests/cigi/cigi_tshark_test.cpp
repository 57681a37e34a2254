// SPDX-License-Identifier: MIT
// Wireshark's CIGI dissector reads what this code writes: datagrams are wrapped in UDP (text2pcap, ports
// 8004/8005), decoded with `tshark -d udp.port==8004,cigi -T fields`, and every field is compared with the
// value encoded. IG -> host (Start of Frame, Weather Conditions and Aerosol Concentration Responses, from the
// IgEncoder) and host -> IG (every packet the IG reads), in both byte orders. Skipped, saying so, when tshark
// or text2pcap (Debian packages tshark, wireshark-common) are not installed.
#include "cigi_samples.h"

#include "skyservice/cigi/cigi_encoder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <utility>

namespace sky::cigi
{
namespace
{

using namespace sky::cigi::test;
namespace fs = std::filesystem;

using FieldTable = std::vector<std::pair<std::string, double>>;  // tshark field name, expected value

bool haveTool(const char* name)
{
    return std::system((std::string("command -v ") + name + " >/dev/null 2>&1").c_str()) == 0;
}

std::string runCapture(const std::string& command)
{
    std::string out;
    if (FILE* pipe = popen(command.c_str(), "r"))
    {
        char buffer[4096];
        size_t n;
        while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0)
            out.append(buffer, n);
        pclose(pipe);
    }
    return out;
}

// text2pcap's input: each datagram as offset + hex bytes, 16 a line; a new offset 0 starts the next one.
void appendHexDump(std::string& text, const std::vector<uint8_t>& datagram)
{
    char cell[32];
    for (size_t i = 0; i < datagram.size(); ++i)
    {
        if (i % 16 == 0)
        {
            std::snprintf(cell, sizeof cell, "%s%06zx", i ? "\n" : "", i);
            text += cell;
        }
        std::snprintf(cell, sizeof cell, " %02x", datagram[i]);
        text += cell;
    }
    text += "\n\n";
}

// Runs text2pcap + tshark on `datagrams` sent from `srcPort` to `dstPort`; one line of fields per datagram.
std::vector<std::vector<std::string>> dissect(const std::vector<std::vector<uint8_t>>& datagrams, int srcPort,
                                              int dstPort, const FieldTable& fields, const std::string& tag)
{
    const fs::path dir = fs::temp_directory_path() / ("sky-cigi-tshark-" + std::to_string(getpid()));
    fs::create_directories(dir);
    std::string hex;
    for (const auto& d : datagrams)
        appendHexDump(hex, d);
    const fs::path txt = dir / (tag + ".txt"), pcap = dir / (tag + ".pcap"), err = dir / (tag + ".err");
    std::ofstream(txt) << hex;
    std::string command = "text2pcap -q -u " + std::to_string(srcPort) + "," + std::to_string(dstPort) + " " +
                          txt.string() + " " + pcap.string() + " 2>" + err.string() + " && tshark -r " +
                          pcap.string() + " -d udp.port==8004,cigi -T fields -E separator=/t -E occurrence=f";
    for (const auto& f : fields)
        command += " -e " + f.first;
    command += " 2>>" + err.string();
    const std::string out = runCapture(command);
    std::vector<std::vector<std::string>> rows;
    std::istringstream lines(out);
    for (std::string line; std::getline(lines, line);)
    {
        std::vector<std::string> row;
        std::istringstream cells(line);
        for (std::string cell; std::getline(cells, cell, '\t');)
            row.push_back(cell);
        rows.push_back(row);
    }
    if (rows.size() != datagrams.size())
    {
        std::ifstream errFile(err);
        ADD_FAILURE() << "tshark gave " << rows.size() << " rows for " << datagrams.size()
                      << " datagrams; stderr: " << std::string(std::istreambuf_iterator<char>(errFile), {});
    }
    fs::remove_all(dir);
    return rows;
}

void expectFields(const std::vector<std::string>& row, const FieldTable& fields, const char* what)
{
    ASSERT_EQ(row.size(), fields.size()) << what;
    for (size_t i = 0; i < fields.size(); ++i)
    {
        const double expected = fields[i].second;
        char* end = nullptr;
        const double got = std::strtod(row[i].c_str(), &end);
        EXPECT_TRUE(!row[i].empty() && *end == '\0') << what << " " << fields[i].first << " = '" << row[i] << "'";
        // Floats print with about 7 significant digits.
        EXPECT_NEAR(got, expected, 1e-6 * std::max(1.0, std::abs(expected))) << what << " " << fields[i].first;
    }
}

FieldTable igToHostFields(const StartOfFrame& s, const WeatherConditionsResponse& w,
                          const AerosolConcentrationResponse& a)
{
    return {
        {"cigi.version", s.majorVersion},
        {"cigi.sof.minor_version", s.minorVersion},
        {"cigi.sof.db_number", s.databaseNumber},
        {"cigi.sof.ig_status", s.igStatus},
        {"cigi.sof.ig_mode", s.igMode},
        {"cigi.sof.timestamp_valid", s.timestampValid},
        {"cigi.sof.earth_reference_model", s.earthReferenceModelCustom},
        {"cigi.sof.ig_frame_number", s.igFrameNumber},
        {"cigi.sof.timestamp", s.timestamp10us},
        {"cigi.sof.last_host_frame_number", s.lastHostFrameNumber},
        {"cigi.wea_cond_response.request_id", w.requestId},
        {"cigi.wea_cond_response.humidity", w.humidityPct},
        {"cigi.wea_cond_response.air_temp", w.airTemperatureC},
        {"cigi.wea_cond_response.visibility_range", w.visibilityM},
        {"cigi.wea_cond_response.horiz_speed", w.horizontalWindMps},
        {"cigi.wea_cond_response.vert_speed", w.verticalWindMps},
        {"cigi.wea_cond_response.wind_direction", w.windDirectionDeg},
        {"cigi.wea_cond_response.barometric_pressure", w.pressureHpa},
        {"cigi.aerosol_concentration_response.request_id", a.requestId},
        {"cigi.aerosol_concentration_response.layer_id", a.layerId},
        {"cigi.aerosol_concentration_response.aerosol_concentration", a.aerosolGPerM3},
    };
}

TEST(CigiTshark, EncoderOutputReadsBackInWiresharksDissector)
{
    if (!haveTool("tshark") || !haveTool("text2pcap"))
        GTEST_SKIP() << "tshark or text2pcap is not installed (Debian packages tshark, wireshark-common): "
                        "the Wireshark cross-check of the CIGI encoder is skipped";
    // Frames 0 and 1 big-endian, frame 2 little-endian: the dissector must follow the byte-swap magic.
    std::vector<std::vector<uint8_t>> datagrams;
    std::vector<FieldTable> expected;
    IgEncoder encoder(ByteOrder::Big);
    for (int frame = 0; frame < 3; ++frame)
    {
        encoder.setByteOrder(frame < 2 ? ByteOrder::Big : ByteOrder::Little);
        StartOfFrame sof = sampleStartOfFrame();
        const uint32_t lastHostFrame = 0x55667788u + static_cast<uint32_t>(frame);
        const double timeS = 1234.5 + 0.02 * frame;
        encoder.beginFrame(lastHostFrame, timeS, sof);
        WeatherConditionsResponse w = sampleWeatherConditionsResponse();
        w.visibilityM += static_cast<float>(frame);
        AerosolConcentrationResponse a = sampleAerosolConcentrationResponse();
        a.layerId = static_cast<uint8_t>(frame);
        encoder.add(w);
        encoder.add(a);
        datagrams.push_back(encoder.datagram());
        sof.igFrameNumber = static_cast<uint32_t>(frame);
        sof.lastHostFrameNumber = lastHostFrame;
        sof.timestamp10us = timestampTicks10us(timeS);
        expected.push_back(igToHostFields(sof, w, a));
    }
    const auto rows = dissect(datagrams, 8004, 8005, expected[0], "ig");
    ASSERT_EQ(rows.size(), 3u);
    for (size_t i = 0; i < rows.size(); ++i)
        expectFields(rows[i], expected[i], i < 2 ? "big-endian frame" : "little-endian frame");
}

FieldTable hostToIgFields()
{
    const IgControl ig = sampleIgControl();
    const EntityControl e = sampleEntityControl();
    const CelestialSphereControl c = sampleCelestialSphereControl();
    const AtmosphereControl a = sampleAtmosphereControl();
    const EnvironmentalRegionControl r = sampleEnvironmentalRegionControl();
    const WeatherControl w = sampleWeatherControl();
    const ViewControl vc = sampleViewControl();
    const ViewDefinition vd = sampleViewDefinition();
    const EnvironmentalConditionsRequest q = sampleEnvironmentalConditionsRequest();
    return {
        {"cigi.ig_control.db_number", ig.databaseNumber},
        {"cigi.ig_control.ig_mode", ig.igMode},
        {"cigi.ig_control.timestamp_valid", ig.timestampValid},
        {"cigi.ig_control.extrapolation_enable", ig.extrapolationEnable},
        {"cigi.ig_control.minor_version", ig.minorVersion},
        {"cigi.ig_control.host_frame_number", ig.hostFrameNumber},
        {"cigi.ig_control.timestamp", ig.timestamp10us},
        {"cigi.ig_control.last_ig_frame_number", ig.lastIgFrameNumber},
        {"cigi.entity_control.entity_id", e.entityId},
        {"cigi.entity_control.entity_state", e.entityState},
        {"cigi.entity_control.attach_state", e.attached},
        {"cigi.entity_control.inherit_alpha", e.inheritAlpha},
        {"cigi.entity_control.ground_ocean_clamp", e.groundOceanClamp},
        {"cigi.entity_control.animation_dir", e.animationBackward},
        {"cigi.entity_control.animation_loop_mode", e.animationContinuous},
        {"cigi.entity_control.animation_state", e.animationState},
        {"cigi.entity_control.extrapolation_enable", e.extrapolationEnable},
        {"cigi.entity_control.alpha", e.alpha},
        {"cigi.entity_control.entity_type", e.entityType},
        {"cigi.entity_control.parent_id", e.parentId},
        {"cigi.entity_control.roll", e.rollDeg},
        {"cigi.entity_control.pitch", e.pitchDeg},
        {"cigi.entity_control.yaw", e.yawDeg},
        {"cigi.entity_control.lat_xoff", e.latDegOrXM},
        {"cigi.entity_control.lon_yoff", e.lonDegOrYM},
        {"cigi.entity_control.alt_zoff", e.altMslMOrZM},
        {"cigi.celestial_sphere_control.hour", c.hour},
        {"cigi.celestial_sphere_control.minute", c.minute},
        {"cigi.celestial_sphere_control.ephemeris_enable", c.ephemerisEnable},
        {"cigi.celestial_sphere_control.sun_enable", c.sunEnable},
        {"cigi.celestial_sphere_control.moon_enable", c.moonEnable},
        {"cigi.celestial_sphere_control.star_enable", c.starFieldEnable},
        {"cigi.celestial_sphere_control.date_time_valid", c.dateTimeValid},
        {"cigi.celestial_sphere_control.date", c.dateMMDDYYYY},
        {"cigi.celestial_sphere_control.star_intensity", c.starFieldIntensityPct},
        {"cigi.atmosphere_control.atmospheric_model_enable", a.atmosphericModelEnable},
        {"cigi.atmosphere_control.humidity", a.humidityPct},
        {"cigi.atmosphere_control.air_temp", a.airTemperatureC},
        {"cigi.atmosphere_control.visibility_range", a.visibilityM},
        {"cigi.atmosphere_control.horiz_wind", a.horizontalWindMps},
        {"cigi.atmosphere_control.vert_wind", a.verticalWindMps},
        {"cigi.atmosphere_control.wind_direction", a.windDirectionDeg},
        {"cigi.atmosphere_control.barometric_pressure", a.pressureHpa},
        {"cigi.env_region_control.region_id", r.regionId},
        {"cigi.env_region_control.region_state", r.regionState},
        {"cigi.env_region_control.merge_weather", r.mergeWeather},
        {"cigi.env_region_control.merge_aerosol", r.mergeAerosol},
        {"cigi.env_region_control.merge_maritime", r.mergeMaritime},
        {"cigi.env_region_control.merge_terrestrial", r.mergeTerrestrial},
        {"cigi.env_region_control.lat", r.latDeg},
        {"cigi.env_region_control.lon", r.lonDeg},
        {"cigi.env_region_control.size_x", r.sizeXM},
        {"cigi.env_region_control.size_y", r.sizeYM},
        {"cigi.env_region_control.corner_radius", r.cornerRadiusM},
        {"cigi.env_region_control.rotation", r.rotationDeg},
        {"cigi.env_region_control.transition_perimeter", r.transitionPerimeterM},
        {"cigi.weather_control.entity_region_id", w.entityOrRegionId},
        {"cigi.weather_control.layer_id", w.layerId},
        {"cigi.weather_control.humidity", w.humidityPct},
        {"cigi.weather_control.weather_enable", w.weatherEnable},
        {"cigi.weather_control.scud_enable", w.scudEnable},
        {"cigi.weather_control.random_winds_enable", w.randomWindsEnable},
        {"cigi.weather_control.random_lightning_enable", w.randomLightningEnable},
        {"cigi.weather_control.cloud_type", w.cloudType},
        {"cigi.weather_control.scope", w.scope},
        {"cigi.weather_control.severity", w.severity},
        {"cigi.weather_control.air_temp", w.airTemperatureC},
        {"cigi.weather_control.visibility_range", w.visibilityM},
        {"cigi.weather_control.scud_frequency", w.scudFrequencyPct},
        {"cigi.weather_control.coverage", w.coveragePct},
        {"cigi.weather_control.base_elevation", w.baseElevationM},
        {"cigi.weather_control.thickness", w.thicknessM},
        {"cigi.weather_control.transition_band", w.transitionBandM},
        {"cigi.weather_control.horiz_wind", w.horizontalWindMps},
        {"cigi.weather_control.vert_wind", w.verticalWindMps},
        {"cigi.weather_control.wind_direction", w.windDirectionDeg},
        {"cigi.weather_control.barometric_pressure", w.pressureHpa},
        {"cigi.weather_control.aerosol_concentration", w.aerosolGPerM3},
        {"cigi.view_control.view_id", vc.viewId},
        {"cigi.view_control.group_id", vc.groupId},
        {"cigi.view_control.xoff_enable", vc.xOffsetEnable},
        {"cigi.view_control.yoff_enable", vc.yOffsetEnable},
        {"cigi.view_control.zoff_enable", vc.zOffsetEnable},
        {"cigi.view_control.roll_enable", vc.rollEnable},
        {"cigi.view_control.pitch_enable", vc.pitchEnable},
        {"cigi.view_control.yaw_enable", vc.yawEnable},
        {"cigi.view_control.entity_id", vc.entityId},
        {"cigi.view_control.xoff", vc.xOffsetM},
        {"cigi.view_control.yoff", vc.yOffsetM},
        {"cigi.view_control.zoff", vc.zOffsetM},
        {"cigi.view_control.roll", vc.rollDeg},
        {"cigi.view_control.pitch", vc.pitchDeg},
        {"cigi.view_control.yaw", vc.yawDeg},
        {"cigi.view_def.view_id", vd.viewId},
        {"cigi.view_def.group_id", vd.groupId},
        {"cigi.view_def.near_enable", vd.nearEnable},
        {"cigi.view_def.far_enable", vd.farEnable},
        {"cigi.view_def.left_enable", vd.leftEnable},
        {"cigi.view_def.right_enable", vd.rightEnable},
        {"cigi.view_def.top_enable", vd.topEnable},
        {"cigi.view_def.bottom_enable", vd.bottomEnable},
        {"cigi.view_def.mirror_mode", vd.mirrorMode},
        {"cigi.view_def.pixel_replication", vd.pixelReplication},
        {"cigi.view_def.projection_type", vd.orthographic},
        {"cigi.view_def.reorder", vd.reorder},
        {"cigi.view_def.view_type", vd.viewType},
        {"cigi.view_def.near", vd.nearM},
        {"cigi.view_def.far", vd.farM},
        {"cigi.view_def.left", vd.leftDeg},
        {"cigi.view_def.right", vd.rightDeg},
        {"cigi.view_def.top", vd.topDeg},
        {"cigi.view_def.bottom", vd.bottomDeg},
        {"cigi.env_cond_request.type", q.requestType},
        {"cigi.env_cond_request.id", q.requestId},
        {"cigi.env_cond_request.lat", q.latDeg},
        {"cigi.env_cond_request.lon", q.lonDeg},
        {"cigi.env_cond_request.alt", q.altMslM},
    };
}

TEST(CigiTshark, HostPacketLayoutsAgreeWithWiresharksDissector)
{
    if (!haveTool("tshark") || !haveTool("text2pcap"))
        GTEST_SKIP() << "tshark or text2pcap is not installed (Debian packages tshark, wireshark-common): "
                        "the Wireshark cross-check of the CIGI packet layouts is skipped";
    std::vector<std::vector<uint8_t>> datagrams;
    for (ByteOrder order : {ByteOrder::Big, ByteOrder::Little})
    {
        std::vector<uint8_t> d;
        encode(sampleIgControl(), order, d);
        encode(sampleEntityControl(), order, d);
        encode(sampleCelestialSphereControl(), order, d);
        encode(sampleAtmosphereControl(), order, d);
        encode(sampleEnvironmentalRegionControl(), order, d);
        encode(sampleWeatherControl(), order, d);
        encode(sampleViewControl(), order, d);
        encode(sampleViewDefinition(), order, d);
        encode(sampleEnvironmentalConditionsRequest(), order, d);
        datagrams.push_back(d);
    }
    const FieldTable fields = hostToIgFields();
    const auto rows = dissect(datagrams, 8005, 8004, fields, "host");
    ASSERT_EQ(rows.size(), 2u);
    expectFields(rows[0], fields, "big-endian host datagram");
    expectFields(rows[1], fields, "little-endian host datagram");
}

} // namespace
} // namespace sky::cigi
