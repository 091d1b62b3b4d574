/* SPDX-License-Identifier: MIT */
/*
 * page.c - the console's page (page.html, one file of HTML, CSS and
 * JavaScript, nothing fetched from elsewhere), built into the program so
 * that strand serve needs no files beside it. The assembler includes the
 * bytes (.incbin, from the project's root, where make runs); the Makefile
 * rebuilds this object when the page changes.
 */
#include "server.h"

__asm__(".section .rodata\n"
	".global serve_page\n"
	".type serve_page, @object\n"
	"serve_page:\n"
	".incbin \"firmware/serve/page.html\"\n"
	".byte 0\n"
	".global serve_page_len\n"
	".type serve_page_len, @object\n"
	".balign 4\n"
	"serve_page_len:\n"
	".long serve_page_len - serve_page - 1\n"
	".previous\n");
