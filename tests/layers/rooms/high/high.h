/* high.h - the top room. */
#ifndef HIGH_H
#define HIGH_H
#include "mid/mid.h"
int high_value(void);
#endif
