/* SPDX-License-Identifier: MIT */
/* libskyclient, files transport: connect, set a view, ask the service to write every frame into a folder,
 * ask for one frame and wait for its JSON sidecar (each file is written atomically, the sidecar last:
 * once it exists, the frame's PNG is complete too). DIR is a folder beneath the service's files_root
 * (the service writes nowhere else); ROOT is that files_root, where this program looks for the files.
 *   example-files --socket /run/user/1000/skyservice.sock --root /run/user/1000/skyservice/frames --dir shots */
#include "skyservice/client/skyclient.h"

#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

static int failed(SkyClient* client, const char* what, SkyResult result)
{
    fprintf(stderr, "example-files: %s failed (%d): %s\n", what, (int)result, sky_client_last_error(client));
    sky_client_close(client);
    return 1;
}

int main(int argc, char** argv)
{
    const char* socket_path = NULL;
    const char* dir = NULL;
    const char* root = NULL;
    for (int i = 1; i + 1 < argc; ++i)
    {
        if (strcmp(argv[i], "--socket") == 0)
            socket_path = argv[i + 1];
        else if (strcmp(argv[i], "--dir") == 0)
            dir = argv[i + 1];
        else if (strcmp(argv[i], "--root") == 0)
            root = argv[i + 1];
    }
    if (!socket_path || !dir || !root)
    {
        fprintf(stderr, "usage: example-files --socket PATH --root FILES_ROOT --dir DIR\n");
        return 2;
    }

    SkyClient* client = NULL;
    SkyResult r = sky_client_connect(socket_path, "example-files", &client);
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
    if ((r = sky_client_subscribe_files(client, dir, 1, "png")) != SKY_OK)
        return failed(client, "subscribe_files", r);
    uint64_t frame = 0;
    if ((r = sky_client_request_frame(client, &frame)) != SKY_OK)
        return failed(client, "request_frame", r);

    char sidecar[4096], path[4096];
    snprintf(sidecar, sizeof sidecar, "%s/%s/frame-%08llu.json", root, dir, (unsigned long long)frame);
    snprintf(path, sizeof path, "%s/%s/frame-%08llu.png", root, dir, (unsigned long long)frame);
    struct stat st;
    for (int waited_ms = 0; stat(sidecar, &st) != 0; waited_ms += 50)
    {
        if (waited_ms > 120000)
        {
            fprintf(stderr, "example-files: %s did not appear within 120 s\n", sidecar);
            sky_client_close(client);
            return 1;
        }
        struct timespec pause = {0, 50 * 1000 * 1000};
        nanosleep(&pause, NULL);
    }
    if (stat(path, &st) != 0)
    {
        fprintf(stderr, "example-files: %s is there but %s is not\n", sidecar, path);
        sky_client_close(client);
        return 1;
    }
    printf("frame %llu: %s, %lld bytes\n", (unsigned long long)frame, path, (long long)st.st_size);
    sky_client_close(client);
    return 0;
}
