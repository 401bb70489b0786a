/* rd_dtoa — doubles as decimal text, fast and exact (rd_dtoa.c).
 *
 * Two spellings of a finite double x, both written without a locale, with
 * the exponent as JSON and jansson write it ("1e-5", "2.5e20": no '+', no
 * leading zeros) and never with a trailing ".0" (rd_json adds one where a
 * real must not read as an integer):
 *   rd_dtoa_shortest  the fewest significant digits that strtod reads back
 *                     as x (of those, the ones nearest x), in whichever of
 *                     fixed and exponent notation is shorter;
 *   rd_dtoa_digits    x rounded to `digits` (1..17, clamped) significant
 *                     digits: the text printf("%.<digits>g") gives, exponent
 *                     respelled as above.
 * Both write at most RD_DTOA_SIZE bytes with the NUL into `buf` and return
 * the length; a non-finite x gives "null" (JSON has no spelling for it). */
#ifndef RD_DTOA_H
#define RD_DTOA_H

#define RD_DTOA_SIZE 32

int rd_dtoa_shortest(double x, char *buf);
int rd_dtoa_digits(double x, int digits, char *buf);

#endif
