// SPDX-License-Identifier: MIT
// Ray / spherical-shell intersection around the eye, written so that float32 is enough at earth
// radius (docs/datums.md). A ray starts at the eye, at distance rc = R + hc from the sphere centre, with
// mu = cosine of its zenith angle. The distances t to the sphere of radius R + hs solve
//   t^2 + 2 rc mu t + c = 0,  c = rc^2 - (R + hs)^2 = (hc - hs)(2R + hc + hs)
// The product form of c avoids subtracting two ~4e13 numbers, and the roots are taken as q and c/q
// with q = -(b + sign(b) sqrt(disc)) (Numerical Recipes 5.6) so that neither cancels.

// Both roots of the ray/sphere equation, nearest first. Returns false when the ray misses the sphere.
bool raySphereRoots(float rc, float mu, float hc, float hs, float R, OUT(float) tNear, OUT(float) tFar)
{
    SKY_ASSERT(rc > 0.0f);
    float b = rc * mu;
    float c = (hc - hs) * (2.0f * R + hc + hs);
    float disc = b * b - c;
    if (disc < 0.0f)
    {
        tNear = -1.0f;
        tFar = -1.0f;
        return false;
    }
    float s = sqrt(disc);
    float q = b >= 0.0f ? -(b + s) : -(b - s);
    float t0 = q;
    float t1 = q != 0.0f ? c / q : 0.0f;
    tNear = min(t0, t1);
    tFar = max(t0, t1);
    return true;
}

// Distance along the ray to the ground sphere (h = 0), or -1 when the ray does not reach it. An eye at or
// below the ground looking down is already there (0): such rays must stop at once, not march the shell.
float rayGroundDistance(float rc, float mu, float hc, float R)
{
    if (hc <= 0.0f)
        return mu < 0.0f ? 0.0f : -1.0f;
    float tNear;
    float tFar;
    if (!raySphereRoots(rc, mu, hc, 0.0f, R, tNear, tFar))
        return -1.0f;
    return tNear > 0.0f ? tNear : -1.0f;
}

// The first stretch of the ray inside the shell hMin <= h <= hMax, cut at the ground and at tMax.
// Returns false when the ray never enters the shell before the ground or tMax.
bool rayShellInterval(float mu, float hc, float hMin, float hMax, float R, float tMax, OUT(float) tEnter,
                      OUT(float) tExit)
{
    float rc = R + hc;
    float innerNear;
    float innerFar;
    float outerNear;
    float outerFar;
    bool hitsInner = raySphereRoots(rc, mu, hc, hMin, R, innerNear, innerFar);
    bool hitsOuter = raySphereRoots(rc, mu, hc, hMax, R, outerNear, outerFar);
    float tGround = rayGroundDistance(rc, mu, hc, R);
    tEnter = 0.0f;
    tExit = 0.0f;
    if (hc < hMin)
    {
        // Below the shell: leave the inner sphere (upwards or along a long grazing path) then the outer.
        tEnter = innerFar;
        tExit = outerFar;
        if (tGround >= 0.0f && tGround < tEnter)
            return false;
    }
    else if (hc <= hMax)
    {
        // Inside: from the eye to the outer sphere, or down to the inner one. A ray heading into the inner
        // sphere (its far root ahead) leaves through the base at the near root; an eye on the base has that
        // root at 0 and no stretch left, not one through the earth to the far side of the outer sphere.
        tEnter = 0.0f;
        tExit = outerFar;
        if (hitsInner && innerFar > 0.0f)
            tExit = max(innerNear, 0.0f);
    }
    else
    {
        // Above: enter the outer sphere, leave through the inner one or back out of the outer one.
        if (!hitsOuter || outerFar <= 0.0f)
            return false;
        tEnter = max(outerNear, 0.0f);
        tExit = hitsInner && innerNear > 0.0f ? innerNear : outerFar;
    }
    tExit = min(tExit, tMax);
    return tExit > tEnter;
}
