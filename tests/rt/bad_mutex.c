/* SPDX-License-Identifier: MIT */
/* bad_mutex.c - self-test input of the real-time check: an rt function
 * that takes a mutex another thread may hold. It must be refused as "a
 * lock". */
#include <pthread.h>

#include "hal/rt.h"

int rt_test_mutex(int x);

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static int shared;

int STRAND_RT rt_test_mutex(int x)
{
	int v;

	pthread_mutex_lock(&lock);
	v = shared += x;
	pthread_mutex_unlock(&lock);
	return v;
}
