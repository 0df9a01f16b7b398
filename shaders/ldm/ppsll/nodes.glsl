// PPSLL storage: the single data buffer of thesis §3.4.1 (Figure 8), laid out exactly like
// PSPPSLL's so that both structures answer queries with ldm/psppsll/query.glsl:
//   data[0 .. LDM_HEADS_TOTAL)             head node of every pixel of every view (0 = empty)
//   data[LDM_HEADS_TOTAL + 2 (n - 1) + 0]  next node of node n (n >= 1; 0 ends the list)
//   data[LDM_HEADS_TOTAL + 2 (n - 1) + 1]  depth of node n (float bits)
#ifndef LDM_PPSLL_NODES_GLSL
#define LDM_PPSLL_NODES_GLSL

uint ppsll_next_slot(uint node) { return LDM_HEADS_TOTAL + 2u * (node - 1u); }
uint ppsll_depth_slot(uint node) { return LDM_HEADS_TOTAL + 2u * (node - 1u) + 1u; }

#endif
