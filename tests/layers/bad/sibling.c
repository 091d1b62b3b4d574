/* sibling.c - a bare name is a header beside the file, and there is none. */
#include "nowhere.h"

int sibling_value(void)
{
	return 0;
}
