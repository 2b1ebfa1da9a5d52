// oscidrum/oscidrum.hpp: the whole public API.
#pragma once

#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/flow.hpp"
#include "oscidrum/friction.hpp"
#include "oscidrum/kinematics.hpp"
#include "oscidrum/metrics.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/parameters.hpp"
#include "oscidrum/record.hpp"
#include "oscidrum/result.hpp"
#include "oscidrum/simulate.hpp"
#include "oscidrum/soil.hpp"
#include "oscidrum/state.hpp"
#include "oscidrum/study.hpp"
#include "oscidrum/transmissibility.hpp"
#include "oscidrum/version.hpp"
