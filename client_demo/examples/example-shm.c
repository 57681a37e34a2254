/* SPDX-License-Identifier: MIT */
/* libskyclient, shared-memory transport: connect, set a view, take one frame, say whether it was torn.
 *   example-shm --socket /run/user/1000/skyservice.sock */
#include "skyservice/client/skyclient.h"

#include <stdio.h>
#include <string.h>

static int failed(SkyClient* client, const char* what, SkyResult result)
{
    fprintf(stderr, "example-shm: %s failed (%d): %s\n", what, (int)result, sky_client_last_error(client));
    sky_client_close(client);
    return 1;
}

int main(int argc, char** argv)
{
    const char* socket_path = NULL;
    for (int i = 1; i + 1 < argc; ++i)
        if (strcmp(argv[i], "--socket") == 0)
            socket_path = argv[i + 1];
    if (!socket_path)
    {
        fprintf(stderr, "usage: example-shm --socket PATH\n");
        return 2;
    }

    SkyClient* client = NULL;
    SkyResult r = sky_client_connect(socket_path, "example-shm", &client);
    if (r != SKY_OK)
        return failed(NULL, "connect", r);

    SkyView view;
    memset(&view, 0, sizeof view);
    view.lat_deg = 47.45; /* above Zurich airport, looking west */
    view.lon_deg = 8.56;
    view.alt_m = 1500.0;
    view.heading_deg = 270.0;
    view.pitch_deg = 5.0;
    view.fov_deg = 60.0;
    view.width = 160;
    view.height = 90;
    if ((r = sky_client_set_view(client, &view)) != SKY_OK)
        return failed(client, "set_view", r);
    if ((r = sky_client_subscribe_shm(client)) != SKY_OK)
        return failed(client, "subscribe_shm", r);
    uint64_t requested = 0;
    if ((r = sky_client_request_frame(client, &requested)) != SKY_OK)
        return failed(client, "request_frame", r);
    /* Wait for the requested frame (a service rendering at a fixed rate may publish it a bit later). */
    if ((r = sky_client_wait_frame(client, requested > 0 ? requested - 1 : 0, 60000)) != SKY_OK)
        return failed(client, "wait_frame", r);

    SkyFrame frame;
    if ((r = sky_client_acquire_frame(client, &frame)) != SKY_OK)
        return failed(client, "acquire_frame", r);
    double sum = 0.0;
    uint64_t count = 0;
    if (frame.pixels && frame.format == SKY_FORMAT_RGBA8_SRGB)
        for (uint32_t y = 0; y < frame.height; ++y)
            for (uint32_t x = 0; x < frame.width; ++x)
                for (int c = 0; c < 3; ++c, ++count)
                    sum += frame.pixels[(size_t)y * frame.row_bytes + (size_t)x * 4 + (size_t)c];
    const SkyResult released = sky_client_release_frame(client, &frame);
    printf("frame %llu: %ux%u, mean RGB %.2f, shadow map %u texels, %s\n", (unsigned long long)frame.frame_id,
           frame.width, frame.height, count ? sum / (double)count : 0.0, frame.shadow_size,
           released == SKY_OK ? "intact" : "TORN (overwritten while held)");
    sky_client_close(client);
    return released == SKY_OK || released == SKY_ERR_TORN ? 0 : 1;
}
