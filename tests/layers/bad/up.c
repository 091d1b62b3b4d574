/* up.c - checked as a file of the bottom room, it includes the top one's
 * header: the check must name the edge, and the bottom room's view must
 * not compile it. */
#include "high/high.h"

int up_value(void)
{
	return high_value();
}
