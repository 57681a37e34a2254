/* SPDX-License-Identifier: MIT */
/* libskyclient: the C API an image generator uses to drive the sky service and take its frames and
 * cloud shadow maps (skyservice/ipc/PROTOCOL.md). Usable from C and C++; links nothing but libc (the Vulkan import
 * helpers are in skyclient_vulkan.h).
 *
 *   SkyClient* c;
 *   if (sky_client_connect("/run/user/1000/skyservice.sock", "my-ig", &c) != SKY_OK) ...
 *   sky_client_set_view(c, &view);
 *   sky_client_subscribe_shm(c);                    // maps the service's frame ring
 *   sky_client_wait_frame(c, last_id, 1000);        // or poll
 *   SkyFrame f;
 *   if (sky_client_acquire_frame(c, &f) == SKY_OK) {
 *       ... read f.pixels, f.shadow_transmittance (pointers into shared memory) ...
 *       if (sky_client_release_frame(c, &f) == SKY_ERR_TORN) ... the service overwrote it: discard ...
 *   }
 *   sky_client_close(c);
 *
 * A SkyClient is not thread-safe: use one per thread. Every function returns a SkyResult; on failure
 * sky_client_last_error() says why in one line. No function blocks longer than the timeout it is given
 * (requests wait at most SKY_CLIENT_REPLY_TIMEOUT_MS for the service's reply).
 */
#ifndef SKY_CLIENT_H
#define SKY_CLIENT_H

#include <stddef.h>
#include <stdint.h>

#include "skyservice/ipc/shm_layout.h"

#ifdef __cplusplus
extern "C" {
#endif

#define SKY_CLIENT_PROTOCOL_VERSION 1
#define SKY_CLIENT_REPLY_TIMEOUT_MS 5000

typedef enum SkyResult
{
    SKY_OK = 0,
    SKY_ERR_ARGUMENT = -1,   /* a null pointer or a value out of range was passed */
    SKY_ERR_CONNECT = -2,    /* no service at the socket path, or the handshake failed */
    SKY_ERR_CLOSED = -3,     /* the service closed the connection (restarted?): reconnect */
    SKY_ERR_TIMEOUT = -4,    /* no reply / no new frame within the timeout */
    SKY_ERR_REFUSED = -5,    /* the service answered with an error (the message says which field) */
    SKY_ERR_PROTOCOL = -6,   /* the service's reply was not understood (version mismatch?) */
    SKY_ERR_NO_FRAME = -7,   /* subscribed, but no frame has been published yet */
    SKY_ERR_TORN = -8,       /* the frame was overwritten while it was held: discard what was read */
    SKY_ERR_SHM = -9,        /* the shared-memory ring could not be mapped or has a bad header */
    SKY_ERR_VULKAN = -10     /* importing exported memory failed (skyclient_vulkan.h) */
} SkyResult;

typedef struct SkyClient SkyClient;

/* The view to render. Same names and units as the socket API's "view" object. Zero it before filling
 * it; for a display wall's off-centre channel set asymmetric = 1 and left/right/up/down_deg instead of
 * fov_deg (shm_layout.h SkyShmView). */
typedef SkyShmView SkyView;

/* One compositing layer of a frame (SKY_LAYER_*, shm_layout.h says what each holds). */
typedef struct SkyFrameLayer
{
    uint32_t format;          /* SKY_FORMAT_*; 0 = not in this frame (pixels null) */
    uint32_t row_bytes;
    const uint8_t* pixels;    /* width x height pixels of the frame, top row first */
} SkyFrameLayer;

/* A frame held by the client. Pointers stay valid until release (or close); the data may be torn
 * if the client holds it longer than (slot_count - 1) frame intervals: release says so. */
typedef struct SkyFrame
{
    uint64_t frame_id;
    double sim_time_unix_s;
    double exposure;
    SkyView view;
    uint32_t format;                   /* SKY_FORMAT_* */
    uint32_t width, height, row_bytes;
    const uint8_t* pixels;
    uint32_t shadow_size;              /* 0 = no shadow map in this frame */
    const float* shadow_transmittance; /* shadow_size^2 floats, north row first */
    SkyShmShadowGeoRef shadow;
    SkyFrameLayer layers[SKY_LAYER_COUNT]; /* [SKY_LAYER_DISPLAY] is `pixels`; the others when subscribed */
    uint32_t slot;                     /* for release: which slot, and its sequence at acquire */
    uint64_t sequence;
} SkyFrame;

/* Connects to the service's control socket and says hello. */
SkyResult sky_client_connect(const char* socket_path, const char* client_name, SkyClient** out_client);
/* Closes the connection and unmaps everything. Null is allowed. */
void sky_client_close(SkyClient* client);
/* One line: why the last call failed ("" after success). Valid until the next call. With NULL: why
 * this thread's last sky_client_connect failed. */
const char* sky_client_last_error(const SkyClient* client);

/* Sends the whole view (set_view): pose, size, and fov_deg or, with asymmetric = 1, the four half-angles. */
SkyResult sky_client_set_view(SkyClient* client, const SkyView* view);
/* Sets the simulated UTC time (s since 1970) and how fast it runs (sim seconds per real second; 0 =
 * frozen, 1 = real time). */
SkyResult sky_client_set_time(SkyClient* client, double unix_time_s, double rate);
/* Asks the service to load a weather snapshot file (written by sky-ingest). The reply only says the
 * request was queued; sky_client_status shows when the weather changed. */
SkyResult sky_client_load_weather(SkyClient* client, const char* snapshot_path);
/* Asks for one frame now (services configured with render rate 0 render only on request); returns the
 * frame id it will have. */
SkyResult sky_client_request_frame(SkyClient* client, uint64_t* out_frame_id);
/* Writes the latest frame to PREFIX.png/.exr/.json (and -shadow.*) on the service's side; PREFIX is a name
 * beneath the service's files_root ("shots/a"; no absolute path, no "..": PROTOCOL.md "Files"). */
SkyResult sky_client_write_files(SkyClient* client, const char* prefix);
/* The service's status reply (a JSON object, NUL-terminated) copied into buffer. */
SkyResult sky_client_status(SkyClient* client, char* buffer, size_t buffer_bytes);

/* Files transport: the service writes every `every`-th frame (>= 1) into `dir` (an existing folder beneath
 * the service's files_root, named relative to it) as DIR/frame-NNNNNNNN.png and/or .exr ("png", "exr" or "both") plus a .json sidecar, each
 * written atomically (temporary file + rename), the .json last: once it exists, the frame's images do too. */
SkyResult sky_client_subscribe_files(SkyClient* client, const char* dir, uint32_t every, const char* format);

/* Shared-memory transport: maps the ring. Call once; after a service restart, reconnect. */
SkyResult sky_client_subscribe_shm(SkyClient* client);
/* The same, asking for compositing layers as well: `layers` is a bit set of (1u << SKY_LAYER_*) (the
 * display layer is always published to shm subscribers). Frames carry the union of what the service's subscribers ask for;
 * a layer costs GPU and copy time only while someone asks for it. May be called again to add layers. */
SkyResult sky_client_subscribe_shm_layers(SkyClient* client, uint32_t layers);
/* Waits until a frame newer than after_frame_id is published (timeout_ms < 0: forever). Sleeps on the
 * ring's publish futex: it returns as soon as the service publishes, without polling. */
SkyResult sky_client_wait_frame(SkyClient* client, uint64_t after_frame_id, int timeout_ms);
/* The newest complete frame, without copying. SKY_ERR_NO_FRAME before the first. */
SkyResult sky_client_acquire_frame(SkyClient* client, SkyFrame* out_frame);
/* SKY_OK when the frame was intact for the whole time it was held, SKY_ERR_TORN when not. */
SkyResult sky_client_release_frame(SkyClient* client, const SkyFrame* frame);

/* Zero-copy transport (VK_KHR_external_memory_fd): the service's exported images, as file
 * descriptors received over the socket (SCM_RIGHTS). The client owns the fds (close them, or hand
 * them to vkAllocateMemory, which takes ownership). skyclient_vulkan.h imports them. */
#define SKY_MAX_EXPORTED_SLOTS 4
typedef struct SkyExportedImage
{
    int memory_fd;                /* VkDeviceMemory exported as an opaque fd */
    uint64_t allocation_bytes;    /* allocationSize to import with */
    uint32_t memory_type_bits;    /* the exporter's memoryTypeBits (pick the same kind of type) */
    uint32_t vk_format;           /* VkFormat of the image */
    uint32_t width, height;
    uint32_t linear_tiling;       /* 1 = VK_IMAGE_TILING_LINEAR with row_pitch, 0 = OPTIMAL */
    uint64_t row_pitch;
} SkyExportedImage;

typedef struct SkyExportedFrames
{
    uint32_t slot_count;                         /* images in the ring */
    SkyExportedImage frame[SKY_MAX_EXPORTED_SLOTS];
    SkyExportedImage shadow[SKY_MAX_EXPORTED_SLOTS];  /* shadow-map images (R32_SFLOAT); fd -1 if none */
    int timeline_semaphore_fd;   /* -1 when the device cannot export semaphores (lavapipe): then a
                                    slot is published in the ring only after the GPU finished it */
    uint8_t device_uuid[16];     /* the exporting VkPhysicalDevice's deviceUUID: import on the same */
    uint8_t driver_uuid[16];
    /* Appended fields (sky_client_subscribe_vulkan, for programs built before them, writes none of these).
     * The compositing layers of sky_client_subscribe_vulkan_layers, as layer[SKY_LAYER_*][slot]: SKY is
     * VK_FORMAT_R16G16B16A16_SFLOAT linear, CLOUDS R16G16B16A16_SFLOAT premultiplied + alpha, DEPTH
     * VK_FORMAT_R32G32_SFLOAT metres (front, weighted distance); shm_layout.h says what each holds. Same
     * size as `frame`, the frame in the top-left corner. memory_fd is -1 for a layer not exported, and
     * always in layer[SKY_LAYER_DISPLAY] (the display layer is `frame`). */
    uint32_t layers;             /* the layers exported to this client, bit k = SKY_LAYER_k (display always) */
    SkyExportedImage layer[SKY_LAYER_COUNT][SKY_MAX_EXPORTED_SLOTS];
} SkyExportedFrames;

/* Subscribes to the zero-copy transport and receives the fds. The ring's sequence locks and
 * latest-slot fields (the shared-memory header, mapped by this call too) say which exported slot
 * holds which frame: acquire/release work the same, with SkyFrame.pixels null. */
SkyResult sky_client_subscribe_vulkan(SkyClient* client, SkyExportedFrames* out_frames);
/* The same, with compositing layers exported as well: `layers` is a bit set of (1u << SKY_LAYER_*) (the
 * display layer is always exported). Each costs GPU time (and memory: an image per slot at the service's
 * largest frame size) only while some subscriber asks for it; it is copied on the GPU, never read back,
 * unless a shared-memory subscriber asks for it too. Every frame published after this call returned
 * holds the layers in its slot's images. May be called again to add layers: each call sends fds for the
 * layers it asks for (and the frame images again). */
SkyResult sky_client_subscribe_vulkan_layers(SkyClient* client, uint32_t layers, SkyExportedFrames* out_frames);

#ifdef __cplusplus
}
#endif

#endif /* SKY_CLIENT_H */
