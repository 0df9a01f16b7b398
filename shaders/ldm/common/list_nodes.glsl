// The storage of the linked-list structures (PPSLL and PSPPSLL): the single data buffer of
// thesis §3.4.1 (Figure 8) with all views in it (§3.4.4); ldm_impls/common/list_node_pool.h
// sizes it.
//   data[0 .. LDM_HEADS_TOTAL)             head node of every pixel of every view (0 = empty)
//   data[LDM_HEADS_TOTAL + 2 (n - 1) + 0]  next node of node n (n >= 1; 0 ends the list)
//   data[LDM_HEADS_TOTAL + 2 (n - 1) + 1]  depth of node n (float bits)
#ifndef LDM_LIST_NODES_GLSL
#define LDM_LIST_NODES_GLSL

uint list_next_slot(uint node) { return LDM_HEADS_TOTAL + 2u * (node - 1u); }
uint list_depth_slot(uint node) { return LDM_HEADS_TOTAL + 2u * (node - 1u) + 1u; }

#endif
