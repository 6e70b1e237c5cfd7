/* SPDX-License-Identifier: GPL-3.0-or-later */
/* granflow — mathematical constants shared by the library, its programs and
 * tests (one definition instead of a DEG/PI macro per file). */
#ifndef GRANFLOW_CONSTANTS_H
#define GRANFLOW_CONSTANTS_H

#define GF_PI 3.14159265358979323846
#define GF_DEG (GF_PI / 180.0)     /* one degree in radians */
#define GF_RAD2DEG (180.0 / GF_PI) /* one radian in degrees */

#endif
