/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "keepFreedMemory.H"

#ifdef __GLIBC__
#include <malloc.h>
#endif

void Foam::granflow::keepFreedMemory()
{
#ifdef __GLIBC__
    if (!mallopt(M_MMAP_THRESHOLD, 1 << 30))
    {
        mallopt(M_MMAP_THRESHOLD, 32 << 20);   // the cap of older glibc
    }
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    mallopt(M_TOP_PAD, 64 << 20);
#endif
}
