/* SPDX-License-Identifier: MIT */
/* bad_none.c - self-test input of the real-time check: objects without a
 * single rt function (the tag forgotten everywhere, STRAND_RT defined
 * away, the wrong objects given). The check must not pass by finding
 * nothing to check. */
int rt_test_forgot_the_tag(int x);

int rt_test_forgot_the_tag(int x)
{
	return x + 1;
}
