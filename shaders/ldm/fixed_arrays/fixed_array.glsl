// Layout shared by PPFLA and PSPPFLA (thesis §3.2.6): FA_K entries per LDM pixel of every
// view, pixel-major, the location k * pixel + i of §3.2.6 with all views' pixels in a row.
#ifndef FIXED_ARRAY_GLSL
#define FIXED_ARRAY_GLSL

uint fa_entry(uint pixel, uint i) { return pixel * FA_K + i; }

#endif
