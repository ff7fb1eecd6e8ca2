// Seventeenth session: how long a thread pinned on CPU 1 takes to wake after a condition
// variable signal from CPU 0, its core idle (or, with an argument, running a SCHED_IDLE
// spinner): gcc -O2 -pthread wl.c -o wl && ./wl && ./wl spin
#define _GNU_SOURCE
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>
#include <sched.h>
#include <stdatomic.h>
static pthread_mutex_t m = PTHREAD_MUTEX_INITIALIZER;
static pthread_cond_t c = PTHREAD_COND_INITIALIZER;
static int go = 0; static double sent, lat[2000]; static int n = 0; static atomic_int spin_stop = 0;
static double now(){struct timespec t; clock_gettime(CLOCK_MONOTONIC,&t); return t.tv_sec*1e6+t.tv_nsec/1e3;}
static void pin(int cpu){cpu_set_t s; CPU_ZERO(&s); CPU_SET(cpu,&s); pthread_setaffinity_np(pthread_self(),sizeof s,&s);}
static void* waiter(void*a){ pin(1); for(;;){ pthread_mutex_lock(&m); while(go==0) pthread_cond_wait(&c,&m); if(go<0){pthread_mutex_unlock(&m);break;} go=0; lat[n++]=now()-sent; pthread_mutex_unlock(&m);} return 0;}
static void* spinner(void*a){ pin(1); struct sched_param p={0}; sched_setscheduler(0, SCHED_IDLE, &p); while(!spin_stop) ; return 0;}
int main(int argc,char**argv){ int spin = argc>1; pin(0); pthread_t t,s; pthread_create(&t,0,waiter,0); if(spin) pthread_create(&s,0,spinner,0);
 for(int i=0;i<1000;i++){ usleep(2000); pthread_mutex_lock(&m); sent=now(); go=1; pthread_cond_signal(&c); pthread_mutex_unlock(&m);}
 usleep(5000); pthread_mutex_lock(&m); go=-1; pthread_cond_signal(&c); pthread_mutex_unlock(&m); pthread_join(t,0); spin_stop=1;
 int cmp(const void*a,const void*b){double x=*(double*)a,y=*(double*)b;return x<y?-1:x>y;} qsort(lat,n,sizeof(double),cmp);
 double sum=0; for(int i=0;i<n;i++) sum+=lat[i];
 printf("%s n=%d mean %.1f us p50 %.1f p90 %.1f p99 %.1f\n", spin?"spin":"idle", n, sum/n, lat[n/2], lat[n*9/10], lat[n*99/100]); }
