/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * gfGmtBatch: GMT modules run one after another in one process (one GMT
 * session, modern mode), for gfReportMaps: a map is some twenty module
 * calls, and as separate `gmt` processes each paid the loading of GMT and
 * its libraries again (most of a map's time).
 *
 *   gfGmtBatch FILE      (or - for standard input)
 *
 * FILE: one module call a line, the module's name then its arguments,
 * separated by TAB characters (so that an argument may hold spaces: a
 * title); empty lines and lines starting with '#' are skipped.  The
 * session's name is GMT_SESSION_NAME's, as for the `gmt` program.  Stops at
 * the first module that fails, naming the line and the module; exit status
 * 0 when every call succeeded.
 */
#include <gmt/gmt.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_ARGS = 256 };

int main(int argc, char** argv)
{
    if (argc != 2 || strcmp(argv[1], "-help") == 0 || strcmp(argv[1], "--help") == 0) {
        fprintf(argc == 2 ? stdout : stderr,
                "usage: gfGmtBatch FILE   (one GMT module call a line: the module, then its\n"
                "                          arguments, TAB-separated; FILE - : standard input)\n");
        return argc == 2 ? 0 : 2;
    }
    FILE* in = strcmp(argv[1], "-") == 0 ? stdin : fopen(argv[1], "r");
    if (!in) {
        fprintf(stderr, "gfGmtBatch: %s: %s\n", argv[1], strerror(errno));
        return 1;
    }
    /* modern mode (gmt begin ... gmt end), errors returned, not exit() */
    void* api = GMT_Create_Session("gfGmtBatch", 2U, GMT_SESSION_NOEXIT | GMT_SESSION_RUNMODE, NULL);
    if (!api) {
        fprintf(stderr, "gfGmtBatch: GMT could not start a session\n");
        if (in != stdin) fclose(in);
        return 1;
    }
    char* line = NULL;
    size_t cap = 0;
    long nline = 0;
    int status = 0;
    while (getline(&line, &cap, in) >= 0) {
        ++nline;
        line[strcspn(line, "\r\n")] = '\0';
        if (line[0] == '\0' || line[0] == '#') continue;
        char* args[MAX_ARGS];
        int n = 0;
        for (char* tok = line; tok != NULL;) {
            char* tab = strchr(tok, '\t');
            if (tab) *tab = '\0';
            char* here = tok;
            tok = tab ? tab + 1 : NULL;
            if (*here == '\0') continue;
            if (n == MAX_ARGS) {
                fprintf(stderr, "gfGmtBatch: %s line %ld: more than %d arguments\n", argv[1], nline, MAX_ARGS - 1);
                status = 1;
                break;
            }
            args[n++] = here;
        }
        if (status) break;
        /* the module's argument count as the mode, its arguments as argv
           (GMT_MODULE_CMD, a single string, for a module without any) */
        int err = n > 1 ? GMT_Call_Module(api, args[0], n - 1, args + 1)
                        : GMT_Call_Module(api, args[0], GMT_MODULE_CMD, NULL);
        if (err != GMT_NOERROR) {
            fprintf(stderr, "gfGmtBatch: %s line %ld: gmt %s failed (GMT error %d)\n", argv[1], nline, args[0], err);
            status = 1;
            break;
        }
    }
    free(line);
    if (in != stdin) fclose(in);
    if (GMT_Destroy_Session(api) != GMT_NOERROR && status == 0) status = 1;
    return status;
}
