// SPDX-License-Identifier: MIT
// The cloud genera, numbered as CIGI 3.3's Weather Control "Cloud Type" numbers them (0-10; 11-15 are
// IG-defined), which the weather snapshot, the weather window's type channel and the shaders use alike
// (docs/model.md). One list for GLSL (the CLOUD_TYPE_* numbers) and C++ (sky::CloudType, the same numbers).
#ifndef SKY_SHARED_CLOUD_TYPE_H
#define SKY_SHARED_CLOUD_TYPE_H

#define CLOUD_TYPE_NONE 0
#define CLOUD_TYPE_ALTOCUMULUS 1
#define CLOUD_TYPE_ALTOSTRATUS 2
#define CLOUD_TYPE_CIRROCUMULUS 3
#define CLOUD_TYPE_CIRROSTRATUS 4
#define CLOUD_TYPE_CIRRUS 5
#define CLOUD_TYPE_CUMULONIMBUS 6
#define CLOUD_TYPE_CUMULUS 7
#define CLOUD_TYPE_NIMBOSTRATUS 8
#define CLOUD_TYPE_STRATOCUMULUS 9
#define CLOUD_TYPE_STRATUS 10

#ifdef __cplusplus
#include <cstdint>

namespace sky
{

enum class CloudType : uint8_t
{
    None = CLOUD_TYPE_NONE,
    Altocumulus = CLOUD_TYPE_ALTOCUMULUS,
    Altostratus = CLOUD_TYPE_ALTOSTRATUS,
    Cirrocumulus = CLOUD_TYPE_CIRROCUMULUS,
    Cirrostratus = CLOUD_TYPE_CIRROSTRATUS,
    Cirrus = CLOUD_TYPE_CIRRUS,
    Cumulonimbus = CLOUD_TYPE_CUMULONIMBUS,
    Cumulus = CLOUD_TYPE_CUMULUS,
    Nimbostratus = CLOUD_TYPE_NIMBOSTRATUS,
    Stratocumulus = CLOUD_TYPE_STRATOCUMULUS,
    Stratus = CLOUD_TYPE_STRATUS,
};

} // namespace sky
#endif

#endif
