#!/bin/sh
# gpiod-api.sh - the one place that decides HAVE_GPIOD_V2: whether the
# installed libgpiod is 2.x (API v2) or older (1.x, API v1), from
# pkg-config's version of it. Prints the implementation of hal/gpio/gpio_line.h
# to compile: hal/gpio/gpiod/gpio_line_v2.c or hal/gpio/gpiod/gpio_line_v1.c.
# --have prints HAVE_GPIOD_V2=1 or HAVE_GPIOD_V2=0 instead.
set -eu
v=$(pkg-config --modversion libgpiod) || {
	echo "gpiod-api: pkg-config knows no libgpiod (apt-get install libgpiod-dev)" >&2
	exit 1
}
case $v in
0.* | 1.*) have=0 ;;
*) have=1 ;;
esac
if [ "${1:-}" = --have ]; then
	echo "HAVE_GPIOD_V2=$have"
elif [ $have = 1 ]; then
	echo hal/gpio/gpiod/gpio_line_v2.c
else
	echo hal/gpio/gpiod/gpio_line_v1.c
fi
