/* SPDX-License-Identifier: MIT */
/*
 * gpio_line.h - lines of one GPIO chip requested together through libgpiod:
 * the one interface the GPIO backend (gpio_dout.c, gpio_din.c) is written
 * against.
 *
 * libgpiod changed its whole API between 1.x (Debian 12: 1.6) and 2.x: the
 * two implementations are hal/gpiod/gpio_line_v1.c and gpio_line_v2.c, and
 * the build compiles exactly one of them, chosen once from the installed
 * library's version (mk/gpio.mk: HAVE_GPIOD_V2). Nothing else in strand
 * knows which API is underneath, and there is no version test in any
 * source file.
 *
 * Levels here are physical (true = high): polarity is the HAL backend's
 * business, done the same way over either API (the v1 API can only give a
 * whole request one active-low flag).
 *
 * Lines are named by offset or by the name the kernel gives them (the
 * device tree's gpio-line-names). The chip is a name (gpiochip0), a path
 * (/dev/gpiochip0), a label (pinctrl-bcm2711) or a number; without a chip,
 * named lines are looked for on every chip, and must all be on one.
 *
 * Error messages name the chip and the line, and for a line held by
 * someone else, who holds it (gpioinfo's consumer).
 */
#ifndef HAL_GPIO_LINE_H
#define HAL_GPIO_LINE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* The most lines one request may hold: libgpiod 1.x's bulk limit. */
#define GPIO_LINE_MAX 64

struct gpio_line_cfg {
	const char *name; /* the line's name on the chip, or NULL: offset */
	uint32_t offset;
};

enum gpio_req_kind {
	GPIO_REQ_OUTPUT,      /* driven to cfg.initial from the request on */
	GPIO_REQ_INPUT_EDGES, /* inputs with edge events on both edges */
};

struct gpio_req_cfg {
	const char *chip;     /* see above; NULL: find named lines anywhere */
	const char *consumer; /* what gpioinfo shows as holding the lines */
	enum gpio_req_kind kind;
	uint32_t nlines;      /* 1 .. GPIO_LINE_MAX */
	const struct gpio_line_cfg *lines;
	const bool *initial;  /* outputs: each line's level from the request on */
};

/* An edge on an input line, as the kernel saw it. */
struct gpio_line_event {
	uint32_t line; /* index into the request's lines */
	bool rising;
	int64_t ts_ns; /* CLOCK_MONOTONIC, taken by the kernel at the edge */
};

struct gpio_req;

/*
 * [init] Open the chip, resolve the lines and request them. 0 and *out, or
 * a negative errno with a message in err naming the chip and the line:
 * -ENOENT no such chip or line name, -EINVAL an offset past the chip's
 * lines, -EBUSY a line held (by whom), -EXDEV named lines on two chips.
 */
int gpio_req_open(struct gpio_req **out, const struct gpio_req_cfg *cfg, char *err,
		  size_t errsize);
/* [init] Release the lines and close the chip. NULL is fine. */
void gpio_req_close(struct gpio_req *r);

/* The chip's kernel name (gpiochip0) and a line's offset on it, resolved. */
const char *gpio_req_chip(const struct gpio_req *r);
uint32_t gpio_req_offset(const struct gpio_req *r, uint32_t line);

/* [rt] Drive every output line of the request at once (one ioctl, nothing
 * allocated): 0 or a negative errno. On a chip that sleeps the ioctl
 * waits for a bus transaction (the backend refuses such a chip for
 * triggers unless allowed: gpio.h). */
int gpio_req_set(struct gpio_req *r, const bool *high);
/* [init] Read every line's level now. */
int gpio_req_get(struct gpio_req *r, bool *high);

/* [init] The descriptors to poll() for edge events (POLLIN), up to max:
 * how many. v1 has one per line, v2 one per request. */
uint32_t gpio_req_fds(const struct gpio_req *r, int *fds, uint32_t max);
/* [event thread] Read the edge events waiting on fds[k] into ev (up to
 * max, never blocking for more): how many, or a negative errno. */
int gpio_req_read(struct gpio_req *r, uint32_t k, struct gpio_line_event *ev, uint32_t max);

/* The library's version, for `strand info` and messages. */
const char *gpio_line_lib_version(void);

/* ---- shared by the two implementations (gpiod/gpio_line_msg.c) ---- */

/* Format "chip gpiochip0 line 5 ('cam-trigger')" style messages into err:
 * returns code. */
int gpio_line_fail(char *err, size_t errsize, int code, const char *chip,
		   const struct gpio_line_cfg *l, const char *fmt, ...)
	__attribute__((format(printf, 6, 7)));
/* The message for a request refused with EBUSY: who holds the line. */
int gpio_line_busy(char *err, size_t errsize, const char *chip, const struct gpio_line_cfg *l,
		   uint32_t offset, const char *consumer);

#endif /* HAL_GPIO_LINE_H */
