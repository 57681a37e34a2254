/* SPDX-License-Identifier: MIT */
/* The ring's layout as a C compiler sees it (C clients include shm_layout.h): compared with C++. */
#include <stddef.h>

#include "skyservice/ipc/shm_layout.h"

size_t skyTestCLayout(int what);

size_t skyTestCLayout(int what)
{
    switch (what)
    {
    case 0: return sizeof(SkyShmHeader);
    case 1: return sizeof(SkyShmSlot);
    case 2: return sizeof(SkyShmView);
    case 3: return sizeof(SkyShmShadowGeoRef);
    case 4: return offsetof(SkyShmHeader, latest_frame_id);
    case 5: return offsetof(SkyShmSlot, shadow);
    case 6: return offsetof(SkyShmSlot, image_offset);
    case 7: return offsetof(SkyShmView, left_deg);
    case 8: return offsetof(SkyShmView, asymmetric);
    case 9: return offsetof(SkyShmHeader, publish_futex);
    default: return 0;
    }
}
