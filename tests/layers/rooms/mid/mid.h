/* mid.h - the middle room, on the bottom one. */
#ifndef MID_H
#define MID_H
#include "low/low.h"
int mid_value(void);
#endif
