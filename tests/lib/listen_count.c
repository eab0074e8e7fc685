/* listen_count PORTFILE COUNTFILE SECONDS: listens on 127.0.0.1 at a free port (written to PORTFILE) and
 * keeps COUNTFILE holding the number of connections made to it, for SECONDS or until SIGTERM. Each
 * connection is answered with nothing and closed. tests/trust/trust_gis.sh counts what a stranger's file makes
 * fathom connect to with it; only loopback is ever listened on. */
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

static volatile sig_atomic_t stop;
static void on_term(int sig) { (void)sig; stop = 1; }

static int write_number(const char *path, long n)
{
    char tmp[4096];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f || fprintf(f, "%ld\n", n) < 0 || fclose(f) != 0)
        return -1;
    return rename(tmp, path);
}

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: listen_count PORTFILE COUNTFILE SECONDS\n");
        return 2;
    }
    signal(SIGTERM, on_term);
    int s = socket(AF_INET, SOCK_STREAM, 0);
    struct sockaddr_in a = {.sin_family = AF_INET, .sin_port = 0, .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    socklen_t len = sizeof a;
    if (s < 0 || bind(s, (struct sockaddr *)&a, sizeof a) != 0 || listen(s, 64) != 0 ||
        getsockname(s, (struct sockaddr *)&a, &len) != 0) {
        perror("listen_count");
        return 1;
    }
    long count = 0;
    if (write_number(argv[2], count) != 0 || write_number(argv[1], ntohs(a.sin_port)) != 0) {
        perror("listen_count");
        return 1;
    }
    time_t end = time(NULL) + atol(argv[3]);
    while (!stop && time(NULL) < end) {
        struct pollfd p = {.fd = s, .events = POLLIN};
        if (poll(&p, 1, 200) > 0) {
            int c = accept(s, NULL, NULL);
            if (c >= 0) {
                close(c);
                write_number(argv[2], ++count);
            }
        }
    }
    close(s);
    return 0;
}
