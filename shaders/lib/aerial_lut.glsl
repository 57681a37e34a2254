// SPDX-License-Identifier: MIT
// Reading the aerial-perspective LUT (shaders/atmosphere/aerial_perspective_lut.comp.glsl) for a view
// direction and a distance. Both 3D LUTs are sampled with a linear REPEAT sampler: u (azimuth) wraps,
// v and w are kept between the first and last texel centres, so nothing wraps there. Closer than the
// first slice (~1 km) the air is taken as growing linearly from none at the eye. The direction comes as
// its zenith angle, acos(dirEnu.z), and enuAzimuth(dirEnu), which the composite has from the sky-view read.
void sampleAerialLut(sampler3D inscatterLut, sampler3D transmittanceLut3d, IN(AtmosphereParams) p, float zenithRad,
                     float azimuthRad, float camRM, float distanceM, OUT(vec3) inscatter, OUT(vec3) transmittance)
{
    float u = fract(azimuthRad / (2.0f * SKY_PI));
    float v = unitRangeToTexCoord(skyViewUnitV(p, camRM, zenithRad), float(AERIAL_LUT_HEIGHT));
    float slice = aerialSliceOfDistance(distanceM);
    float w = (clamp(slice, 0.0f, float(AERIAL_LUT_SLICES - 1)) + 0.5f) / float(AERIAL_LUT_SLICES);
    inscatter = textureLod(inscatterLut, vec3(u, v, w), 0.0f).rgb;
    transmittance = textureLod(transmittanceLut3d, vec3(u, v, w), 0.0f).rgb;
    if (slice < 0.0f)
    {
        float f = slice + 1.0f;  // 0 at the eye, 1 at the first slice
        inscatter *= f;
        transmittance = mix(vec3(1.0f), transmittance, f);
    }
}
