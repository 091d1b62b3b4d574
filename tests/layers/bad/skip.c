/* skip.c - checked as a file of the top room, it reaches past the middle
 * one: the room below the one below is not its to include, though its
 * view holds it (through mid.h). */
#include "low/low.h"

int skip_value(void)
{
	return low_value();
}
