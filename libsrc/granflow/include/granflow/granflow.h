/* SPDX-License-Identifier: GPL-3.0-or-later */
/* granflow — umbrella header: the whole public API of libgranflow. */
#ifndef GRANFLOW_GRANFLOW_H
#define GRANFLOW_GRANFLOW_H

#include "granflow/constants.h"
#include "granflow/status.h"
#include "granflow/earth_pressure.h"
#include "granflow/source.h"
#include "granflow/friction.h"
#include "granflow/mass_exchange.h"
#include "granflow/topography.h"
#include "granflow/exact.h"
#include "granflow/standard_tests.h"
#include "granflow/kinetic1d.h"
#include "granflow/dg1d.h"
#include "granflow/sh1d.h"
#include "granflow/surface.h"
#include "granflow/ensemble.h"
#include "granflow/calibration.h"
#include "granflow/version.h" /* GF_VERSION_STRING, gf_version() */
/* test and benchmark helpers: granflow/verification.h */


#endif
