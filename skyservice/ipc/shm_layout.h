/* SPDX-License-Identifier: MIT */
/* The shared-memory frame ring (skyservice/ipc/PROTOCOL.md): the byte layout that the service writes
 * and libskyclient reads. Plain C so that C clients can include it; every field has a fixed size and the
 * structs have no implicit padding (static_asserts in skyservice/ipc/shm_ring.cpp).
 *
 * One POSIX shared-memory object (shm_open name given in the `subscribed` reply) holds:
 *
 *   offset 0                       SkyShmHeader
 *   header.slots_offset + i*stride SkyShmSlot i (i < slot_count), each followed in its stride by
 *     slot.image_offset            the frame: width*height pixels, row_bytes per row, top row first
 *     slot.layers[k].offset        the compositing layers a subscriber asked for (SKY_LAYER_*)
 *     slot.shadow_offset           the shadow map: shadow_size^2 float32 key-light transmittance,
 *                                  north row first, west column first (0 = opaque, 1 = clear)
 * Every slot has room for every layer at the ring's largest size; pages of layers never written are
 * never touched, so they cost no memory.
 *
 * Concurrency: one writer (the service), any number of readers, nobody ever blocks. Each slot has a
 * sequence lock: the writer makes `sequence` odd, writes the slot, makes it even again (release
 * stores), and then publishes the slot in header.latest_slot / latest_frame_id. A reader loads
 * `sequence` (acquire); odd means "being written, take another"; it reads what it needs and loads
 * `sequence` again: a different value means the writer came round and the read is torn. The writer
 * fills the slots round robin, so a reader has (slot_count - 1) frame intervals to finish a read.
 * Waiting for a frame: when `features` has SKY_SHM_FEATURE_PUBLISH_FUTEX, the writer adds 1 to
 * `publish_futex` after every publish and wakes every FUTEX_WAIT on that word (Linux futex on a shared
 * mapping; a read-only mapping may wait). A reader loads the word, checks latest_frame_id, and only then
 * waits while the word still holds what it loaded, so no publish is missed; it bounds each wait (e.g.
 * 20 ms) to notice a writer that died. Without the feature, a reader polls latest_frame_id.
 * Atomic fields are accessed with __atomic_load_n / __atomic_store_n (GCC/Clang builtins, valid in C
 * and C++) because C11 _Atomic and std::atomic do not share a layout guarantee.
 */
#ifndef SKY_SHM_LAYOUT_H
#define SKY_SHM_LAYOUT_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define SKY_SHM_MAGIC 0x31304D5246594B53ull /* "SKYFRM01" read as little-endian bytes */
#define SKY_SHM_VERSION 2u

/* Bits of SkyShmHeader.features. */
#define SKY_SHM_FEATURE_PUBLISH_FUTEX 1u /* publish_futex counts publishes and wakes its waiters */

/* Pixel formats of SkyShmSlot.format. */
#define SKY_FORMAT_RGBA8_SRGB 1u      /* tone-mapped display frame, 4 bytes per pixel, alpha 255 */
#define SKY_FORMAT_RGBA16F_LINEAR 2u  /* linear radiance (pre-exposed), half floats, 8 bytes per pixel */
#define SKY_FORMAT_RGBA16F_PREMULTIPLIED 3u /* premultiplied linear radiance (pre-exposed) + alpha, half floats */
#define SKY_FORMAT_R32F_METRES 4u     /* one float32 per pixel, metres (no layer uses it since the depth layer
                                         became SKY_FORMAT_RG32F_METRES) */
#define SKY_FORMAT_RG32F_METRES 5u    /* two float32 per pixel, metres, 8 bytes per pixel */

/* The layers of a frame (SkyShmSlot.layers[i]), each present when some subscriber asked for it:
 *   DISPLAY  SKY_FORMAT_RGBA8_SRGB: the finished picture (tone-mapped, sRGB, alpha 255), as before layers.
 *   SKY      SKY_FORMAT_RGBA16F_LINEAR: the sky alone (atmosphere, sun and moon disks), no clouds, alpha 1.
 *   CLOUDS   SKY_FORMAT_RGBA16F_PREMULTIPLIED: the clouds as the eye sees them through the air in front of
 *            them (aerial perspective applied), premultiplied; alpha = 1 - cloud transmittance. Over the
 *            sky layer: linear = sky * (1 - a) + clouds.rgb.
 *   DEPTH    SKY_FORMAT_RG32F_METRES: two distances of the cloud along the pixel's ray (metres from the
 *            eye), both 0 where alpha is 0. R: the cloud's front, where the opacity accumulated from the eye
 *            first reaches 2 % (the weighted distance where it never does; never beyond it): an object at
 *            distance d < R is fully in front of the cloud. G: the transmittance-weighted distance (the
 *            single value this layer held before the front was added).
 * Linear values are pre-exposed: divide by SkyShmSlot.exposure for W m^-2 sr^-1 nm^-1. */
#define SKY_LAYER_DISPLAY 0u
#define SKY_LAYER_SKY 1u
#define SKY_LAYER_CLOUDS 2u
#define SKY_LAYER_DEPTH 3u
#define SKY_LAYER_COUNT 4u

/* The view a frame was rendered for. Names and units as in skyservice/ipc/PROTOCOL.md (CLI, socket API, sidecar JSON).
 * The frustum is either symmetric (asymmetric = 0: fov_deg vertical, the horizontal from the image's
 * aspect) or off-centre, as the channels of a display wall (asymmetric = 1: the angles from the view
 * axis to the left, right, upper and lower image edges, each in (-85, 85) degrees, positive outwards,
 * left + right and up + down > 1; a frame then reports fov_deg = up_deg + down_deg). Zero the whole
 * struct before filling it: a symmetric view leaves the last five fields 0. */
typedef struct SkyShmView
{
    double lat_deg;      /* geodetic latitude of the eye (degrees) */
    double lon_deg;      /* longitude of the eye (degrees, [-180, 180)) */
    double alt_m;        /* height above the WGS84 ellipsoid (metres) */
    double heading_deg;  /* clockwise from true north (degrees) */
    double pitch_deg;    /* + nose up (degrees) */
    double roll_deg;     /* + right wing down (degrees) */
    double fov_deg;      /* vertical field of view (degrees) */
    uint32_t width;      /* pixels */
    uint32_t height;     /* pixels */
    double left_deg;     /* asymmetric frustum: half-angles from the view axis (degrees) */
    double right_deg;
    double up_deg;
    double down_deg;
    uint32_t asymmetric; /* 1: left/right/up/down give the frustum and fov_deg is ignored; 0: fov_deg */
    uint32_t reserved;   /* 0 */
} SkyShmView;

/* Where the shadow map's texels lie on the earth (skyservice/render/shadow_map.h): the azimuthal
 * equidistant projection centred at (centre_lat_deg, centre_lon_deg); texel (column c, row r) has
 * easting (c + 0.5 - size/2) * extent_m/size and northing (size/2 - r - 0.5) * extent_m/size. */
typedef struct SkyShmShadowGeoRef
{
    double centre_lat_deg;
    double centre_lon_deg;
    double extent_m;            /* edge length of the square on the ground (metres) */
    double corner_lat_deg[4];   /* corners NW, NE, SE, SW (outer texel edges) */
    double corner_lon_deg[4];
    double sun_azimuth_deg;     /* key light (sun, or the moon at night) when the map was made */
    double sun_elevation_deg;
    uint32_t size_texels;       /* texels per side; 0 = this frame has no shadow map */
    uint32_t light_is_moon;     /* 1 when the key light was the moon */
} SkyShmShadowGeoRef;

typedef struct SkyShmHeader
{
    uint64_t magic;            /* SKY_SHM_MAGIC */
    uint32_t version;          /* SKY_SHM_VERSION */
    uint32_t header_bytes;     /* sizeof(SkyShmHeader) */
    uint32_t slot_count;       /* slots in the ring (>= 2) */
    uint32_t slot_header_bytes;/* sizeof(SkyShmSlot) */
    uint64_t slot_stride;      /* bytes from one slot to the next (a multiple of 4096) */
    uint64_t slots_offset;     /* offset of slot 0 from the start of the object (a multiple of 4096) */
    uint64_t total_bytes;      /* size of the whole object */
    uint32_t max_width;        /* largest frame a slot holds (pixels) */
    uint32_t max_height;
    uint32_t max_shadow_size;  /* largest shadow map a slot holds (texels per side) */
    uint32_t writer_pid;       /* the service's process id */
    uint64_t latest_frame_id;  /* ATOMIC: frame id of the newest complete slot, 0 = none yet */
    uint64_t latest_slot;      /* ATOMIC: index of that slot */
    uint64_t writer_heartbeat_ns; /* ATOMIC: CLOCK_MONOTONIC of the writer's last frame, for liveness */
    uint32_t features;         /* SKY_SHM_FEATURE_* bits the writer provides */
    uint32_t publish_futex;    /* ATOMIC: publishes so far (wraps); the word readers FUTEX_WAIT on */
    uint64_t reserved[7];
} SkyShmHeader;

/* One layer of a slot: width x height pixels (SkyShmSlot.view), row_bytes per row, top row first. */
typedef struct SkyShmLayer
{
    uint32_t format;           /* SKY_FORMAT_*; 0 = not in this frame (bytes 0) */
    uint32_t row_bytes;
    uint64_t offset;           /* from the start of the slot */
    uint64_t bytes;
} SkyShmLayer;

typedef struct SkyShmSlot
{
    uint64_t sequence;         /* ATOMIC: the sequence lock; odd while the writer is in the slot */
    uint64_t frame_id;         /* increases by one per rendered frame, starts at 1 */
    double sim_time_unix_s;    /* UTC of the rendered scene (s since 1970, fractional) */
    double exposure;           /* pre-exposure: linear values / exposure = W m^-2 sr^-1 nm^-1 */
    SkyShmView view;
    uint32_t format;           /* SKY_FORMAT_* */
    uint32_t row_bytes;        /* bytes per image row */
    uint64_t image_offset;     /* from the start of this slot */
    uint64_t image_bytes;
    uint64_t shadow_offset;    /* from the start of this slot; shadow.size_texels^2 floats */
    uint64_t shadow_bytes;     /* 0 when the frame has no shadow map */
    SkyShmShadowGeoRef shadow;
    SkyShmLayer layers[SKY_LAYER_COUNT]; /* layers[SKY_LAYER_DISPLAY] repeats format/row_bytes/image_* */
    uint64_t reserved[4];
} SkyShmSlot;

#ifdef __cplusplus
}
#endif

#endif /* SKY_SHM_LAYOUT_H */
