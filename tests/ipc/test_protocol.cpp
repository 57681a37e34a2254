// SPDX-License-Identifier: MIT
// Request validation (skyservice/ipc/protocol.h against PROTOCOL.md): every error code the parser
// gives, with the field it names, and the reply lines. not_hello is the connection's state, checked
// by the service (skyservice/service/control_loop.cpp), not by this pure parser.
#include "skyservice/ipc/protocol.h"

#include <gtest/gtest.h>

#include <string>

namespace sky
{
namespace
{

ProtocolLimits limits()
{
    ProtocolLimits l;
    l.maxWidth = 640;
    l.maxHeight = 480;
    return l;
}

struct Case
{
    const char* line;
    const char* code;
    const char* field;
};

void expectError(const Case& c)
{
    Request r;
    ProtocolError e;
    EXPECT_FALSE(parseRequest(c.line, limits(), r, e)) << c.line;
    EXPECT_EQ(e.code, c.code) << c.line << " -> " << e.message;
    EXPECT_EQ(e.field, c.field) << c.line << " -> " << e.message;
    EXPECT_FALSE(e.message.empty());
    EXPECT_EQ(e.message.find('\n'), std::string::npos);
    if (*c.field)
    {
        // The message names the field (its last part: "view.lat" says "view.lat").
        EXPECT_NE(e.message.find(c.field), std::string::npos) << e.message;
    }
}

TEST(Protocol, BadJson)
{
    for (const char* line : {"", "not json", "{\"type\":\"hello\"", "[1,2]", "\"hello\"", "42", "null",
                             "{\"type\":\"set_view\",\"view\":{\"lat\":NaN}}", "{\"a\":Infinity}", "{\"a\":1}{}",
                             "{\"type\":\"hello\",\"client\":\"\xff\xfe\"}"})
        expectError({line, "bad_json", ""});
}

TEST(Protocol, BadVersionAndHello)
{
    expectError({R"({"type":"hello","protocol":2})", "bad_version", "protocol"});
    expectError({R"({"type":"hello","protocol":0})", "bad_version", "protocol"});
    expectError({R"({"type":"hello"})", "missing_field", "protocol"});
    expectError({R"({"type":"hello","protocol":"1"})", "bad_type", "protocol"});
    expectError({R"({"type":"hello","protocol":1.5})", "bad_type", "protocol"});
    expectError({R"({"type":"hello","protocol":1,"client":7})", "bad_type", "client"});
    const std::string longName(65, 'x');
    expectError({(R"({"type":"hello","protocol":1,"client":")" + longName + "\"}").c_str(), "out_of_range", "client"});
    Request r;
    ProtocolError e;
    ASSERT_TRUE(parseRequest(R"({"type":"hello","protocol":1,"client":"my-ig","id":"a1"})", limits(), r, e)) << e.message;
    EXPECT_EQ(r.type, RequestType::Hello);
    EXPECT_EQ(r.protocol, 1);
    EXPECT_EQ(r.clientName, "my-ig");
    EXPECT_EQ(r.id, "a1");
}

TEST(Protocol, UnknownType)
{
    expectError({R"({"protocol":1})", "unknown_type", "type"});
    expectError({R"({"type":5})", "unknown_type", "type"});
    expectError({R"({"type":"dance"})", "unknown_type", "type"});
    expectError({R"({"type":"HELLO","protocol":1})", "unknown_type", "type"});
}

TEST(Protocol, MissingField)
{
    expectError({R"({"type":"set_view"})", "missing_field", "view"});
    expectError({R"({"type":"set_view","view":{}})", "missing_field", "view"});
    expectError({R"({"type":"set_view","view":{"latitude":10}})", "missing_field", "view"});
    expectError({R"({"type":"set_time"})", "missing_field", "time"});
    expectError({R"({"type":"load_weather"})", "missing_field", "path"});
    expectError({R"({"type":"subscribe"})", "missing_field", "transport"});
    expectError({R"({"type":"subscribe","transport":"files"})", "missing_field", "dir"});
    expectError({R"({"type":"write_files"})", "missing_field", "prefix"});
}

TEST(Protocol, BadType)
{
    expectError({R"({"type":"set_view","view":[1]})", "bad_type", "view"});
    expectError({R"({"type":"set_view","view":{"lat":"north"}})", "bad_type", "view.lat"});
    expectError({R"({"type":"set_view","view":{"alt":true}})", "bad_type", "view.alt"});
    expectError({R"({"type":"set_view","view":{"fov":null}})", "bad_type", "view.fov"});
    expectError({R"({"type":"set_view","view":{"width":64.5}})", "bad_type", "view.width"});
    expectError({R"({"type":"set_view","view":{"height":"64"}})", "bad_type", "view.height"});
    expectError({R"({"type":"set_time","time":1750000000})", "bad_type", "time"});
    expectError({R"({"type":"set_time","rate":"fast"})", "bad_type", "rate"});
    expectError({R"({"type":"load_weather","path":["a"]})", "bad_type", "path"});
    expectError({R"({"type":"subscribe","transport":1})", "bad_type", "transport"});
    expectError({R"({"type":"subscribe","transport":"files","dir":"/tmp","every":"2"})", "bad_type", "every"});
    expectError({R"({"type":"subscribe","transport":"files","dir":"/tmp","format":1})", "bad_type", "format"});
    expectError({R"({"type":"write_files","prefix":{}})", "bad_type", "prefix"});
    expectError({R"({"type":"status","id":[1]})", "bad_type", "id"});
    expectError({R"({"type":"status","id":{"a":1}})", "bad_type", "id"});
}

TEST(Protocol, OutOfRangeIncludingNonFinite)
{
    const Case cases[] = {
        {R"({"type":"set_view","view":{"lat":90.0001}})", "out_of_range", "view.lat"},
        {R"({"type":"set_view","view":{"lat":-91}})", "out_of_range", "view.lat"},
        {R"({"type":"set_view","view":{"lon":541}})", "out_of_range", "view.lon"},
        {R"({"type":"set_view","view":{"alt":-501}})", "out_of_range", "view.alt"},
        {R"({"type":"set_view","view":{"alt":100001}})", "out_of_range", "view.alt"},
        {R"({"type":"set_view","view":{"heading":721}})", "out_of_range", "view.heading"},
        {R"({"type":"set_view","view":{"heading":-361}})", "out_of_range", "view.heading"},
        {R"({"type":"set_view","view":{"pitch":-90.5}})", "out_of_range", "view.pitch"},
        {R"({"type":"set_view","view":{"roll":180.5}})", "out_of_range", "view.roll"},
        {R"({"type":"set_view","view":{"fov":0.5}})", "out_of_range", "view.fov"},
        {R"({"type":"set_view","view":{"fov":171}})", "out_of_range", "view.fov"},
        {R"({"type":"set_view","view":{"width":7}})", "out_of_range", "view.width"},
        {R"({"type":"set_view","view":{"width":641}})", "out_of_range", "view.width"},
        {R"({"type":"set_view","view":{"height":481}})", "out_of_range", "view.height"},
        {R"({"type":"set_view","view":{"width":-8}})", "out_of_range", "view.width"},
        {R"({"type":"set_view","view":{"lat":10,"width":99999999999999999999}})", "bad_type", "view.width"},
        {R"({"type":"set_time","rate":86401})", "out_of_range", "rate"},
        {R"({"type":"set_time","rate":-86401})", "out_of_range", "rate"},
        {R"({"type":"load_weather","path":"relative/file.skywx"})", "out_of_range", "path"},
        {R"({"type":"subscribe","transport":"carrier-pigeon"})", "out_of_range", "transport"},
        {R"({"type":"subscribe","transport":"files","dir":"/tmp","every":0})", "out_of_range", "every"},
        {R"({"type":"subscribe","transport":"files","dir":"/tmp","format":"tiff"})", "out_of_range", "format"},
        {R"({"type":"write_files","prefix":""})", "out_of_range", "prefix"},
        // JSON has no NaN/inf literals (those are bad_json above); an overflowing number is the way to
        // send a non-finite value, and it is out of range.
        {R"({"type":"set_view","view":{"lat":1e999}})", "out_of_range", ""},
        {R"({"type":"set_time","rate":-1e400})", "out_of_range", ""},
    };
    for (const Case& c : cases)
        expectError(c);
}

// A display wall's channel: the four half-angles instead of fov (PROTOCOL.md "Asymmetric frusta").
TEST(Protocol, AsymmetricFrustumHalfAngles)
{
    Request r;
    ProtocolError e;
    ASSERT_TRUE(parseRequest(R"({"type":"set_view","view":{"left":40,"right":-5.5,"up":20,"down":12,"width":64}})",
                             limits(), r, e))
        << e.message;
    EXPECT_EQ(*r.view.left, 40.0);
    EXPECT_EQ(*r.view.right, -5.5);
    EXPECT_EQ(*r.view.up, 20.0);
    EXPECT_EQ(*r.view.down, 12.0);
    EXPECT_FALSE(r.view.fov.has_value());
    EXPECT_EQ(*r.view.width, 64u);
    // Angles alone are a view change.
    ASSERT_TRUE(parseRequest(R"({"type":"set_view","view":{"left":0,"right":40,"up":20,"down":20}})", limits(), r, e))
        << e.message;
    // All four together, never with fov, each in (-85, 85) (skyservice/render/view_limits.h; the service
    // checks the sums: view_frustum.h validateFrustum).
    const Case cases[] = {
        {R"({"type":"set_view","view":{"left":40,"right":0,"up":20}})", "missing_field", "view.down"},
        {R"({"type":"set_view","view":{"right":40,"up":20,"down":20}})", "missing_field", "view.left"},
        {R"({"type":"set_view","view":{"fov":60,"left":40,"right":0,"up":20,"down":20}})", "out_of_range", "view.fov"},
        {R"({"type":"set_view","view":{"left":85.5,"right":0,"up":20,"down":20}})", "out_of_range", "view.left"},
        {R"({"type":"set_view","view":{"left":0,"right":40,"up":85,"down":20}})", "out_of_range", "view.up"},
        {R"({"type":"set_view","view":{"left":-85,"right":40,"up":20,"down":20}})", "out_of_range", "view.left"},
        {R"({"type":"set_view","view":{"left":0,"right":40,"up":20,"down":-86}})", "out_of_range", "view.down"},
        {R"({"type":"set_view","view":{"left":0,"right":40,"up":"20","down":20}})", "bad_type", "view.up"},
    };
    for (const Case& c : cases)
        expectError(c);
}

TEST(Protocol, ErrorsKeepTheIdAndChangeNothing)
{
    Request r;
    ProtocolError e;
    EXPECT_FALSE(parseRequest(R"({"id":17,"type":"set_view","view":{"lat":45,"lon":999}})", limits(), r, e));
    EXPECT_EQ(e.id, 17);
    EXPECT_FALSE(r.view.lat.has_value()) << "a half-valid view must not escape";
    const nlohmann::json reply = nlohmann::json::parse(errorReply(e));
    EXPECT_EQ(reply["type"], "error");
    EXPECT_EQ(reply["id"], 17);
    EXPECT_EQ(reply["code"], "out_of_range");
    EXPECT_EQ(reply["field"], "view.lon");
    EXPECT_NE(reply["message"].get<std::string>().find("999"), std::string::npos);
    // No id in the request: none in the reply; no field: none either.
    EXPECT_FALSE(parseRequest("garbage", limits(), r, e));
    const nlohmann::json bare = nlohmann::json::parse(errorReply(e));
    EXPECT_FALSE(bare.contains("id"));
    EXPECT_FALSE(bare.contains("field"));
}

TEST(Protocol, ValidRequestsParse)
{
    Request r;
    ProtocolError e;
    ASSERT_TRUE(parseRequest(
        R"({"type":"set_view","id":3,"view":{"lat":47.5,"lon":-540,"alt":-500,"heading":720,"pitch":90,"roll":-180,"fov":1,"width":640,"height":8},"future":"ignored"})",
        limits(), r, e))
        << e.message;
    EXPECT_EQ(r.type, RequestType::SetView);
    EXPECT_EQ(*r.view.lat, 47.5);
    EXPECT_EQ(*r.view.lon, -540.0);
    EXPECT_EQ(*r.view.width, 640u);
    EXPECT_EQ(*r.view.height, 8u);
    // Both ends of fov's range are views the renderer draws (skyservice/render/view_limits.h).
    ASSERT_TRUE(parseRequest(R"({"type":"set_view","view":{"fov":170}})", limits(), r, e)) << e.message;
    EXPECT_EQ(*r.view.fov, 170.0);
    ASSERT_TRUE(parseRequest(R"({"type":"set_view","view":{"fov":60}})", limits(), r, e));
    EXPECT_FALSE(r.view.lat.has_value());
    EXPECT_EQ(*r.view.fov, 60.0);
    ASSERT_TRUE(parseRequest(R"({"type":"set_time","time":"2026-06-21T12:00:00Z","rate":0})", limits(), r, e));
    EXPECT_EQ(*r.timeIso, "2026-06-21T12:00:00Z");
    EXPECT_EQ(*r.rate, 0.0);
    ASSERT_TRUE(parseRequest(R"({"type":"load_weather","path":"/w/a.skywx"})", limits(), r, e));
    EXPECT_EQ(r.path, "/w/a.skywx");
    ASSERT_TRUE(parseRequest(R"({"type":"subscribe","transport":"vulkan"})", limits(), r, e));
    EXPECT_EQ(r.transport, Transport::Vulkan);
    EXPECT_EQ(r.layers, 1u << SKY_LAYER_DISPLAY);
    // Vulkan subscribers name layers as shm ones do (the service exports them as images).
    ASSERT_TRUE(
        parseRequest(R"({"type":"subscribe","transport":"vulkan","layers":["depth","clouds"]})", limits(), r, e));
    EXPECT_EQ(r.layers, (1u << SKY_LAYER_DEPTH) | (1u << SKY_LAYER_CLOUDS));
    EXPECT_FALSE(parseRequest(R"({"type":"subscribe","transport":"vulkan","layers":["fog"]})", limits(), r, e));
    EXPECT_EQ(e.field, "layers");
    ASSERT_TRUE(parseRequest(R"({"type":"subscribe","transport":"files","dir":"/o","every":5,"format":"both"})",
                             limits(), r, e));
    EXPECT_EQ(r.transport, Transport::Files);
    EXPECT_EQ(r.every, 5u);
    EXPECT_EQ(r.fileFormat, "both");
    ASSERT_TRUE(parseRequest(R"({"type":"render"})", limits(), r, e));
    EXPECT_EQ(r.type, RequestType::Render);
    EXPECT_TRUE(r.id.is_null());
    ASSERT_TRUE(parseRequest(R"( {"type":"status","id":"s"} )", limits(), r, e));
    EXPECT_EQ(r.type, RequestType::Status);
    ASSERT_TRUE(parseRequest(R"({"type":"write_files","prefix":"out/x"})", limits(), r, e));
    EXPECT_EQ(r.type, RequestType::WriteFiles);
    EXPECT_EQ(r.path, "out/x");
}

TEST(Protocol, Replies)
{
    Request r;
    r.type = RequestType::Render;
    r.id = "abc";
    nlohmann::json ok = nlohmann::json::parse(okReply(r, {{"frame_id", 12}}));
    EXPECT_EQ(ok["type"], "ok");
    EXPECT_EQ(ok["request"], "render");
    EXPECT_EQ(ok["id"], "abc");
    EXPECT_EQ(ok["frame_id"], 12);
    r.id = nullptr;
    EXPECT_EQ(okReply(r), R"({"request":"render","type":"ok"})");
    r.id = 5;
    nlohmann::json body = nlohmann::json::parse(replyWithId(r, {{"type", "status"}}));
    EXPECT_EQ(body["id"], 5);
    EXPECT_STREQ(requestName(RequestType::LoadWeather), "load_weather");
    // A message with a newline stays one line; a string with invalid UTF-8 does not throw.
    ProtocolError e;
    e.code = "failed";
    e.message = "two\nlines \xff";
    const std::string line = errorReply(e);
    EXPECT_EQ(line.find('\n'), std::string::npos);
    EXPECT_TRUE(nlohmann::json::accept(line));
}

}  // namespace
}  // namespace sky

namespace sky
{
namespace
{

// Regression: an embedded NUL ("\u0000") was kept in the parsed string and silently cut by every C
// API after it (open, the log): "/srv/a.skywx\u0000ignored" loaded /srv/a.skywx. It is refused now.
TEST(Protocol, NulInStringsIsRefused)
{
    expectError({R"({"type":"load_weather","path":"/srv/a.skywx\u0000ignored"})", "out_of_range", "path"});
    expectError({R"({"type":"hello","protocol":1,"client":"ig\u0000x"})", "out_of_range", "client"});
    expectError({R"({"type":"write_files","prefix":"a\u0000b"})", "out_of_range", "prefix"});
    expectError({R"({"type":"subscribe","transport":"files","dir":"d\u0000"})", "out_of_range", "dir"});
}

}  // namespace
}  // namespace sky
