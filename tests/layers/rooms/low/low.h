/* low.h - the bottom room of the layer self-test. */
#ifndef LOW_H
#define LOW_H
int low_value(void);
#endif
