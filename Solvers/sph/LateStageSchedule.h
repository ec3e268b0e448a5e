// The late-stage sound speed over time (docs/physics.md §2.8).
//
// The late-stage law holds the Courant step at h/c, so c sets the late stage's cost; it must
// also stay several times the flow speeds, or the soft material is compressed by the flow it
// should carry. A crater's flow slows as it grows (in point-source scaling the excavation flow
// falls about as t^(−1/(1+μ)), Housen & Holsapple 2011), so one low c chosen for the end of the
// growth is far below the flow at an early switch, and one c high enough at the switch costs
// its ratio to the low one over the whole stage.
//
// With SphParams::lateStageInitialSoundSpeed c0 above lateStageSoundSpeed c1, c follows the flow
// instead: c0 at the switch time t_s, then c0 (t/t_s)^(−q), q = lateStageSoundSpeedExponent,
// taken in stages of a factor 2^(1/4) (c at stage k: c0 2^(−k/4), while it is above the power
// law, so the staged c never falls below it), down to c1, where it stays. Each new stage
// switches the materials again as the first switch does (the lithostatic pressure kept, the
// departure from it and the deviatoric stress scaled by K'/K). The stage is a function of the
// time alone, so a run restored from a checkpoint takes up the stage it was written in.
#pragma once

#include "sph/SphParams.h"

namespace craterkit {

// The late-stage sound speed at time t (t ≥ par.lateStageTime ≥ 0).
double lateStageSoundSpeedAt(const SphParams& par, double t);

} // namespace craterkit
