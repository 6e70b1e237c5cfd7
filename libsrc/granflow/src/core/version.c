/* SPDX-License-Identifier: GPL-3.0-or-later */
/* gf_version: the version the library was built as (granflow/version.h) */
#include "granflow/version.h"

const char *gf_version(void)
{
    return GF_VERSION_STRING;
}
