#!/bin/bash
# The idle share of both CPUs (/proc/stat) while a command runs: idle.sh lgh-render MODEL ...
# usage: statrun.sh CMD...   prints idle % across the command
read -r _ u1 n1 s1 i1 w1 q1 sq1 st1 _ < <(grep '^cpu ' /proc/stat)
"$@"
read -r _ u2 n2 s2 i2 w2 q2 sq2 st2 _ < <(grep '^cpu ' /proc/stat)
tot=$(( (u2-u1)+(n2-n1)+(s2-s1)+(i2-i1)+(w2-w1)+(q2-q1)+(sq2-sq1)+(st2-st1) ))
echo "idle $(( 100*(i2-i1)/tot ))%  user $(( 100*(u2-u1)/tot ))% sys $(( 100*(s2-s1)/tot ))%"
