// DDGI's debug views: the probe volumes' bounds, and every probe as a sphere coloured by its
// irradiance or its state.
#pragma once

#include <vector>

#include "gi/ddgi/probe_field.h"
#include "gi/debug_view.h"

namespace voxgi {

constexpr const char* kProbesView = "probes";

enum class ProbeColor { Irradiance, State };
struct ProbesOptions {
    ProbeColor color = ProbeColor::Irradiance;
};
const SettingsTable<ProbesOptions>& probesOptions();

std::vector<DebugViewInfo> ddgiDebugViews();

// The box through each volume's probe grid.
DebugDrawing probeBounds(const ProbeField& field);
// Irradiance: the probe's mean irradiance / pi (what a white diffuse surface there shows),
// tone-mapped with the exposure; state: green active, blue sleeping, red off.
DebugDrawing probeSpheres(const ProbeField& field, ProbeColor color, float exposureStops);

}  // namespace voxgi
