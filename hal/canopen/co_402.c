/* SPDX-License-Identifier: MIT */
/*
 * co_402.c - the CiA 402 state machine (see co_402.h).
 *
 * Source: CiA 402-2 (= IEC 61800-7-201), the drive's "finite state
 * automaton" with its transitions, and the tables of controlword commands
 * and statusword states:
 *
 *   state                    statusword (x: any)    transitions out
 *                            bit 6 5 4 3 2 1 0
 *   not ready to switch on       0 x x 0 0 0 0      1 (automatic) -> switch on disabled
 *   switch on disabled           1 x x 0 0 0 0      2 shutdown -> ready
 *   ready to switch on           0 1 x 0 0 0 1      3 switch on -> switched on
 *                                                   7 disable voltage, quick stop -> sw. on dis.
 *   switched on                  0 1 x 0 0 1 1      4 enable operation -> operation enabled
 *                                                   6 shutdown -> ready
 *                                                   10 disable voltage, quick stop -> sw. on dis.
 *   operation enabled            0 1 x 0 1 1 1      5 disable operation -> switched on
 *                                                   8 shutdown -> ready
 *                                                   9 disable voltage -> switch on disabled
 *                                                   11 quick stop -> quick stop active
 *   quick stop active            0 0 x 0 1 1 1      12 ramp done (0x605A 1..4), disable
 *                                                      voltage -> switch on disabled
 *                                                   16 enable operation (0x605A 5..8) -> op. en.
 *   fault reaction active        0 x x 1 1 1 1      14 (automatic) -> fault
 *   fault                        0 x x 1 0 0 0      15 fault reset -> switch on disabled
 *   (any)                                           13 a fault -> fault reaction active
 *
 * Bit 4 is "voltage enabled", bit 5 "quick stop" (0 while one is active).
 * The states are told apart by bits 0-3 and 6 (mask 0x4f), and the three
 * that share those by bit 5 as well (mask 0x6f).
 *
 *   command              controlword bit 7 3 2 1 0
 *   shutdown                             0 x 1 1 0
 *   switch on, disable operation         0 0 1 1 1
 *   enable operation                     0 1 1 1 1
 *   disable voltage                      0 x x 0 x
 *   quick stop                           0 x 0 1 x
 *   fault reset                          0 -> 1 (rising edge)
 */
#include "co_402.h"

#include "hal/rt.h"

enum co402_state STRAND_RT co402_decode(uint16_t sw)
{
	switch (sw & 0x4f) {
	case 0x00:
		return CO402_NOT_READY;
	case 0x40:
		return CO402_DISABLED;
	case 0x0f:
		return CO402_FAULT_REACTION;
	case 0x08:
		return CO402_FAULT;
	}
	switch (sw & 0x6f) {
	case 0x21:
		return CO402_READY;
	case 0x23:
		return CO402_SWITCHED_ON;
	case 0x27:
		return CO402_ENABLED;
	case 0x07:
		return CO402_QUICK_STOP;
	}
	/* bit patterns the table does not have (0x01 without bit 5, ...):
	 * nothing a command can be based on */
	return CO402_NOT_READY;
}

uint16_t STRAND_RT co402_state_bits(enum co402_state s)
{
	static const uint16_t bits[] = {
		[CO402_NOT_READY] = 0x00,   [CO402_DISABLED] = 0x40,
		[CO402_READY] = 0x21,	    [CO402_SWITCHED_ON] = 0x23,
		[CO402_ENABLED] = 0x27,	    [CO402_QUICK_STOP] = 0x07,
		[CO402_FAULT_REACTION] = 0x0f, [CO402_FAULT] = 0x08,
	};

	return s <= CO402_FAULT ? bits[s] : 0;
}

static bool STRAND_RT is_shutdown(uint16_t cw)
{
	return (cw & 0x87) == 0x06;
}

static bool STRAND_RT is_switch_on(uint16_t cw)
{
	return (cw & 0x8f) == 0x07;
}

static bool STRAND_RT is_enable(uint16_t cw)
{
	return (cw & 0x8f) == 0x0f;
}

static bool STRAND_RT is_disable_voltage(uint16_t cw)
{
	return (cw & 0x82) == 0x00;
}

static bool STRAND_RT is_quick_stop(uint16_t cw)
{
	return (cw & 0x86) == 0x02;
}

enum co402_state STRAND_RT co402_next(enum co402_state s, uint16_t cw, uint16_t prev,
				      bool quick_stop_stays)
{
	switch (s) {
	case CO402_DISABLED:
		return is_shutdown(cw) ? CO402_READY : s;                /* 2 */
	case CO402_READY:
		if (is_switch_on(cw) || is_enable(cw))
			return CO402_SWITCHED_ON;                        /* 3 */
		if (is_disable_voltage(cw) || is_quick_stop(cw))
			return CO402_DISABLED;                           /* 7 */
		return s;
	case CO402_SWITCHED_ON:
		if (is_enable(cw))
			return CO402_ENABLED;                            /* 4 */
		if (is_shutdown(cw))
			return CO402_READY;                              /* 6 */
		if (is_disable_voltage(cw) || is_quick_stop(cw))
			return CO402_DISABLED;                           /* 10 */
		return s;
	case CO402_ENABLED:
		if (is_switch_on(cw))
			return CO402_SWITCHED_ON;                        /* 5 */
		if (is_shutdown(cw))
			return CO402_READY;                              /* 8 */
		if (is_disable_voltage(cw))
			return CO402_DISABLED;                           /* 9 */
		if (is_quick_stop(cw))
			return CO402_QUICK_STOP;                         /* 11 */
		return s;
	case CO402_QUICK_STOP:
		if (is_disable_voltage(cw))
			return CO402_DISABLED;                           /* 12 */
		if (quick_stop_stays && is_enable(cw))
			return CO402_ENABLED;                            /* 16 */
		return s;
	case CO402_FAULT:
		return (cw & 0x80) && !(prev & 0x80) ? CO402_DISABLED : s; /* 15 */
	default:
		return s; /* not ready, fault reaction: the drive's own doing */
	}
}

uint16_t STRAND_RT co402_toward_enabled(enum co402_state s, uint16_t prev)
{
	switch (s) {
	case CO402_READY:
		return CO402_CW_SWITCH_ON;
	case CO402_SWITCHED_ON:
	case CO402_ENABLED:
		return CO402_CW_ENABLE_OPERATION;
	case CO402_QUICK_STOP:
	case CO402_FAULT_REACTION:
		return CO402_CW_DISABLE_VOLTAGE;
	case CO402_FAULT:
		/* a rising edge: bit 7 low for one cycle if it was high */
		return prev & CO402_CW_FAULT_RESET ? CO402_CW_DISABLE_VOLTAGE :
						     CO402_CW_FAULT_RESET;
	default:
		return CO402_CW_SHUTDOWN;
	}
}

const char *co402_state_name(enum co402_state s)
{
	static const char *const names[] = {
		[CO402_NOT_READY] = "not ready to switch on",
		[CO402_DISABLED] = "switch on disabled",
		[CO402_READY] = "ready to switch on",
		[CO402_SWITCHED_ON] = "switched on",
		[CO402_ENABLED] = "operation enabled",
		[CO402_QUICK_STOP] = "quick stop active",
		[CO402_FAULT_REACTION] = "fault reaction active",
		[CO402_FAULT] = "fault",
	};

	return s <= CO402_FAULT ? names[s] : "?";
}
