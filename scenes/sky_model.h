// Skies as tables of radiance (shaders/shared/sky.h): a clear-sky atmosphere from Preetham,
// Shirley and Smits' analytic model (SIGGRAPH 1999, "A Practical Analytic Model for
// Daylight"), with the sun's colour and irradiance from the same atmosphere's transmittance,
// and equirectangular environment maps read from EXR. See docs/sky.md.
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "scenes/scene.h"

namespace voxgi {

// The model's fitted range: turbidity 2 (very clear) to 10 (hazy), sun above the horizon.
constexpr float kMinTurbidity = 2.0f;
constexpr float kMaxTurbidity = 10.0f;
// Illuminance of the sun outside the atmosphere (lux): the scale between the model's
// luminances and the scene's sun irradiance above the atmosphere.
constexpr double kSolarIlluminanceLux = 128000.0;
// The sun's apparent diameter seen from the Earth (degrees, the yearly mean): the disc of the
// atmosphere's sun light, whose shadows it softens.
constexpr float kSunAngularDiameterDegrees = 0.53f;

struct AtmosphereSky {
    Sky sky;
    glm::vec3 sunIrradiance{0.0f};  // at the ground, on a surface facing the sun (W/m^2)
};

// The sky's table and the sun at the ground. Throws InputError when the sun is not above the
// horizon or the turbidity is outside the model's range.
AtmosphereSky makeAtmosphere(const AtmosphereDesc& desc);

// The atmosphere's sun: the directional light of this name, which the loader adds.
constexpr const char* kAtmosphereSunName = "sun";
// That light when the sky is an atmosphere and the scene has it, else null.
Light* atmosphereSun(Scene& scene);

// When the atmosphere's sun (atmosphereSun) points another way than the sky's table was made for (the viewer moved it), remakes
// the table and the light's colour and irradiance for the new direction, counts the change in
// sky.revision and returns true. A sun at or below the horizon, outside the model's range,
// keeps the last table and colour (false).
bool followSun(Scene& scene);

// Radiance of the clear sky (no ground, no sun disc) arriving from unit direction `towardSky`
// above the horizon, in W/(m^2 sr) for the desc's sun irradiance.
glm::vec3 atmosphereRadiance(const AtmosphereDesc& desc, glm::vec3 towardSky);

// Direct transmittance of the atmosphere (Rayleigh and aerosol extinction) for the sun at
// zenith angle `zenith` (radians), at the red, green and blue wavelengths 612, 549 and 465 nm.
glm::vec3 sunTransmittance(float zenith, float turbidity);

// The direction sunlight travels at solar time `hour` (0..24) of day `day` (1..365) at
// `latitudeDeg` (north positive); +y is up, +x east and -z north. The sun may be below the
// horizon (y > 0).
glm::vec3 solarDirection(float latitudeDeg, float day, float hour);

// An equirectangular EXR (its RGB layer; u = 0 toward +x, v = 0 at the zenith) times `scale`.
// Throws InputError naming the file.
Sky loadEnvmap(const std::string& path, float scale);

// Sets sky.radiance to the table's mean over the sphere (solid-angle weighted).
void computeMeanRadiance(Sky& sky);

}  // namespace voxgi
