/* What a path names, without following a final symbolic link (the output
 * writers write NAME.tmp and rename it over NAME, which must only ever
 * replace a regular file) or following it (the deck reader: a FIFO or a pipe
 * is read to its end), and the real path of a link. */
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* 0: nothing there (or, following links, a dangling link), 1: regular file,
 * 2: symbolic link (only when follow is 0: the final link itself, lstat),
 * 3: directory, 4: anything else (a device, a FIFO, a pipe's /dev/fd/N, a
 * socket: whose size is not known beforehand). follow != 0: what the path
 * names once its symbolic links are followed (stat). */
int sj_path_kind(const char *path, int follow)
{
    struct stat st;
    if ((follow ? stat(path, &st) : lstat(path, &st)) != 0) return 0;
    if (S_ISREG(st.st_mode)) return 1;
    if (S_ISLNK(st.st_mode)) return 2;
    if (S_ISDIR(st.st_mode)) return 3;
    return 4;
}

/* The canonical path of an existing path into out (size cap); its length,
 * or -1 when it cannot be resolved or does not fit. */
int sj_real_path(const char *path, char *out, int cap)
{
    char buf[PATH_MAX];
    if (realpath(path, buf) == NULL) return -1;
    int n = (int)strlen(buf);
    if (n >= cap) return -1;
    memcpy(out, buf, (size_t)n);
    return n;
}
