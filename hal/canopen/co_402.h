/* SPDX-License-Identifier: MIT */
/*
 * co_402.h - the CiA 402 drive state machine: states as the statusword
 * (0x6041) shows them, commands as the controlword (0x6040) gives them, the
 * transitions a drive makes (for the simulated drive) and the command that
 * moves a drive towards "operation enabled" (for the master). co_402.c holds
 * the table, with its source.
 *
 * Everything here is [rt]: pure functions, static strings.
 */
#ifndef CO_402_H
#define CO_402_H

#include <stdbool.h>
#include <stdint.h>

enum co402_state {
	CO402_NOT_READY,      /* not ready to switch on: self-test */
	CO402_DISABLED,       /* switch on disabled */
	CO402_READY,          /* ready to switch on */
	CO402_SWITCHED_ON,    /* switched on: power stage on, no torque */
	CO402_ENABLED,        /* operation enabled: following its targets */
	CO402_QUICK_STOP,     /* quick stop active: braking on its own ramp */
	CO402_FAULT_REACTION, /* fault reaction active */
	CO402_FAULT,
};

/* Controlwords of the commands (bits 7, 3, 2, 1, 0). */
enum {
	CO402_CW_DISABLE_VOLTAGE = 0x0000,
	CO402_CW_QUICK_STOP = 0x0002,
	CO402_CW_SHUTDOWN = 0x0006,
	CO402_CW_SWITCH_ON = 0x0007,        /* also "disable operation" */
	CO402_CW_ENABLE_OPERATION = 0x000f, /* also "switch on + enable operation" */
	CO402_CW_FAULT_RESET = 0x0080,      /* on its rising edge */
};

/* Statusword bits beyond the state. */
enum {
	CO402_SW_VOLTAGE_ENABLED = 0x0010,
	CO402_SW_WARNING = 0x0080,
	CO402_SW_REMOTE = 0x0200,          /* the controlword is obeyed */
	CO402_SW_TARGET_REACHED = 0x0400,
	CO402_SW_FOLLOWS_TARGET = 0x1000,  /* CSP/CSV: the target is followed */
	CO402_SW_FOLLOWING_ERROR = 0x2000, /* CSP */
};

/* Modes of operation (0x6060). */
enum {
	CO402_MODE_CSP = 8, /* cyclic synchronous position */
	CO402_MODE_CSV = 9, /* cyclic synchronous velocity */
};

/* Quick stop option code (0x605A) 2: brake on the quick stop ramp (0x6085),
 * then switch on disabled. */
#define CO402_QUICK_STOP_RAMP_THEN_DISABLE 2

/* The state a statusword shows. */
enum co402_state co402_decode(uint16_t statusword);

/* The state bits of a statusword (0, 1, 2, 3, 5, 6) for state s. */
uint16_t co402_state_bits(enum co402_state s);

/* Drive side: the state after controlword cw in state s, prev the
 * controlword before (a fault reset acts on the rising edge of bit 7).
 * quick_stop_stays: option codes 5..8, where "enable operation" leaves
 * quick stop active. Faults and the end of a quick stop are the drive's
 * own transitions, not commands: they are not here. */
enum co402_state co402_next(enum co402_state s, uint16_t cw, uint16_t prev,
			    bool quick_stop_stays);

/* Master side: the controlword that takes a drive in state s one step
 * towards "operation enabled" (prev: the controlword sent last). */
uint16_t co402_toward_enabled(enum co402_state s, uint16_t prev);

const char *co402_state_name(enum co402_state s);

#endif /* CO_402_H */
