/* mid.c - the middle room: a header below it, by folder and name. */
#include <stdio.h>

#include "low/low.h"
#include "mid.h"

int mid_value(void)
{
	return low_value() + 1;
}
