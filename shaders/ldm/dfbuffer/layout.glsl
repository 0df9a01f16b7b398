// DF-buffer storage (thesis §3.2.10, Figure 11), all views in one set of buffers:
//   counts[p]      fragments of pixel p (count pass); the storing pass counts them back to 0
//   offsets[p]     first slot of pixel p (exclusive prefix sum of counts);
//                  offsets[LDM_HEADS_TOTAL] = the scan's total
//   depths[slot]   the pixels' depths (float bits), back to back, ascending after the sort
// The depth array holds LDM_DF_CAPACITY values, as the sizing policy chose: a range that
// would reach past it (a guess or budget too small) is cut there, and counted.
#ifndef LDM_DFBUFFER_LAYOUT_GLSL
#define LDM_DFBUFFER_LAYOUT_GLSL

#define DF_COUNTS_BINDING LDM_STRUCTURE_BINDING0
#define DF_OFFSETS_BINDING LDM_STRUCTURE_BINDING1
#define DF_DEPTHS_BINDING LDM_STRUCTURE_BINDING2

#endif
