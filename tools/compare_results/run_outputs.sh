#!/bin/bash
# usage: run_outputs.sh BIN ROOT OUT: the outputs compared bit for bit at issue 27 (verify --full, the paper figures, the three
# studies --quick, every shipped case), written with BIN against the tree ROOT into OUT; then
# compare_results.py OLD_OUT NEW_OUT --root OLD_ROOT=NEW_ROOT. (Before issue 27 the study was "inversion" and the case
# liver-relaxation-seed.)
BIN=$1; export TMLAB_ROOT=$2; OUT=$3
mkdir -p $OUT
log=$OUT.log; : > $log
run() { echo "== $* $(date +%T)" >> $log; nice -n 5 "$BIN" "$@" >> $log 2>&1; echo "rc=$? $(date +%T)" >> $log; }
run verify --full --results $OUT/verify
for f in fig5 fig6 fig7; do run paper $f --results $OUT/paper; done
for f in fig2 fig3 table1 table2; do run paper $f --quick --results $OUT/paper; done
run hereditary --quick --results $OUT/studies
run workprecision --quick --results $OUT/studies
run depth-limit --quick --results $OUT/studies
for c in $TMLAB_ROOT/cases/*.json; do n=$(basename $c .json); run run $n --results $OUT/cases --checkpoint-every off; done
echo ALLDONE >> $log
