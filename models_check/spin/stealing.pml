/* stealing.pml — a Promela model of core/'s load-stealing protocol, for SPIN (Debian `spin`).
 *
 * Based on: Kumar, Chang & Manocha, SC'96, §4.2 (the paper's handshake), as implemented in
 * core/stealing_protocol.hpp (owner claim O1-O4, steal T1-T5, install I1-I2), core/try_lock.hpp (L1-L3),
 * core/active_workers.hpp (A1-A3) and core/frame_loop.hpp (E1-E6). Every labelled step below carries the
 * label of core/site.hpp as the first argument of its access (ld/st/sp/xchg/rmw/fence/await: O1, F1, ...);
 * models_check/spin/check_labels.cmake fails when the set of labels used here differs from the stealing sites of
 * core/site.hpp. x86-TSO as explicit per-thread FIFO store buffers (Sewell et al., "x86-TSO", CACM 2010;
 * the store-buffer encoding used for SPIN by e.g. Travkin, Mütze & Wehrheim, "SPIN as a linearizability
 * checker under weak memory models", HVC 2013): a store appends to its thread's buffer; a load reads the
 * thread's newest buffered store to that address, else memory; a Flusher process per thread moves the
 * oldest entry to memory at any time; mfence and locked instructions (xchg, lock xadd) wait until the
 * thread's buffer is empty.
 *
 * CONFIGURATION (cpp defines, see run_proofs.sh)
 *   P        workers (2..3)            N       items (1..4)        FRAMES  frames (1..2)
 *   TSO      0: sequential consistency, 1: x86-TSO with store buffers of depth D = 2
 *   POLICY   SEQCST | FENCED | MINIMAL | ASYM | PAPER: what each site compiles to on x86 (g++ 12):
 *              SEQCST   every store seq_cst = xchg (drains the buffer, then writes memory); F1, F2 mfence
 *              FENCED   stores are plain mov (buffered); F1, F2 seq_cst fences = mfence
 *              MINIMAL  relaxed/release stores and relaxed/acquire loads are the same mov as FENCED; F1, F2
 *                       mfence; relaxed RMWs (A1, A2) are still lock-prefixed. On x86 MINIMAL compiles to
 *                       FENCED's instructions, so the two models coincide (kept as separate runs on purpose).
 *              ASYM     F1 a compiler barrier (nothing); F2 membarrier(PRIVATE_EXPEDITED): drains the thief's
 *                       own buffer, then every other thread's buffer (each drain one atomic step; membarrier
 *                       guarantees each running thread passes a full barrier before the call returns)
 *              PAPER    no StoreLoad fence at all (F1, F2 nothing)
 *   EXACT    1: assert exactly-once (each item run once per frame, checked at every run and at frame end);
 *            0: assert at-least-once only (no item of a frame run zero times)
 *   BOUND_RUNS  1: also assert that no item runs more than twice in a frame
 *   STEAL_BOUND  n > 0: a worker steals at most n times per frame (only for the termination property, see term)
 *   BROKEN_SKIP_REREAD  negative control: the thief keeps its whole share without T4/T5 (Defect::kSkipFrontReread)
 *   WAITFREE 1: the owner-isolation check (see PROPERTIES)
 *   LIVENESS 1: compile the LTL properties (select one with pan -N name)
 *
 * WHAT IS ABSTRACTED (the model is an abstraction of core/, not a translation)
 *   - Items: ids 0..N-1. A list body (core: entries[], ranges with flat positions) is a bitmask of item ids in
 *     increasing order; flat position f is the f-th set bit. Initial lists are block_allocation's contiguous
 *     blocks; later lists are whatever a worker processed (temporal coherence), so bodies of several ranges
 *     appear in frame 2. The body is one memory cell (BODY(w)), written through the store buffer by install
 *     and read by the thief together with T2 (it cannot change while the thief holds LockList) and by the owner
 *     together with O4 (only the owner installs its own list during a frame).
 *   - Processing an item is a ghost counter runs[id], incremented in the same atomic step as O4 (after O4 the
 *     owner runs the item without further shared accesses, so where it runs does not matter for counting).
 *     With -DBATCH=k the owner claims up to k positions per handshake (Owner::try_claim_up_to), and all of
 *     them run in that step.
 *   - LockList is a test-and-set: L1 a load, L2 an xchg (locked: drains the buffer), L3 a store.
 *   - The owner's private copy of Front, the thief's staging (mid, end, copied body) and the per-worker frame
 *     fields are locals/ghost globals. The frame fields that change hands between frames (log, next list) are
 *     ghost globals written directly: their hand-over ordering (E3/E5/E2) is checked by Relacy's `handover`
 *     cell, not here.
 *   - find_work's polling: core's idle worker tries its victims in rounds (try_lock, T1, T2) and reads `active`
 *     (A3) after each round. A failed attempt (kLockBusy, kEmpty) changes no shared cell, so the model lets an
 *     idle worker wait until it can take some victim's free LockList and see Front < End there, or until A3
 *     reads 0; it may pick any victim (a superset of core's seeded order). Failed attempts are not modelled.
 *   - Merged steps (Lipton reduction): L1+L2+T1+T2+copy of the body are one step (the lock acquisition is a
 *     right mover; End and the body cannot change while LockList is held); T5's L3 joins the keep_unclaimed
 *     computation (a release is a left mover); install (L1, L2, body, I1, I2, L3) is one step that writes the
 *     protected cells to memory and buffers only L3 (nobody reads them before taking the lock, which L3's
 *     flush, FIFO-last, gives back). Under SC, F1 and F2 are no-ops.
 *   - The last frame's arriver does not install lists for a frame that never runs.
 *   - Buffers hold at most D = 2 stores; a store to a full buffer waits for a flush. This under-approximates
 *     TSO (deeper buffers admit more reorderings); depth 2 is what the two-store handshake needs.
 *   - Memory models are SC and x86-TSO only: C++ acquire/release (ARM, POWER, load buffering) is not modelled
 *     here; Relacy (models_check/) covers the C++ model, boundedly.
 * WHAT IS NOT CHECKED
 *   core's code itself (this is a hand-written model; the label check only keeps the vocabulary in step),
 *   ItemFailure/exception paths, statistics, range merging/normalization, P > 3, N > 4, FRAMES > 2.
 *
 * PROPERTIES
 *   safety   assertions: exactly-once (EXACT=1) or at-least-once; End never increases between installs (I2);
 *            active never underflows; no invalid end state (every worker finishes both frames).
 *   term     LTL: every frame terminates  -> pan -a -f -N term  (weak fairness). FALSE as core is written: a
 *            lone unclaimed item can be stolen back and forth forever (items_left_to_victim(1) = 0, so a
 *            thief takes a one-item list whole, and the new owner may lose it again before its first claim);
 *            every step of that cycle is fair. With STEAL_BOUND (each worker steals at most n times per
 *            frame) the livelock is cut and term holds.
 *   starve   LTL: a thief waiting at T4 eventually stops waiting -> pan -a -N starve finds the paper's
 *            starvation (the owner preempted inside a claim) without fairness; holds with -f
 *   WAITFREE at any step of any claim, the scheduler may freeze every other worker and the caller (Promela
 *            `provided`): the owner must still finish the claim alone (else: invalid end state) in at most 5
 *            shared accesses (assert) — wait-freedom of the owner path (I6)
 */

#ifndef P
#define P 2
#endif
#ifndef N
#define N 2
#endif
#ifndef FRAMES
#define FRAMES 2
#endif
#ifndef TSO
#define TSO 0
#endif
#define SEQCST 1
#define FENCED 2
#define MINIMAL 3
#define ASYM 4
#define PAPER 5
#ifndef POLICY
#define POLICY FENCED
#endif
#ifndef EXACT
#define EXACT 1
#endif
#ifndef BROKEN_SKIP_REREAD
#define BROKEN_SKIP_REREAD 0
#endif
#ifndef BOUND_RUNS
#define BOUND_RUNS 0
#endif
#ifndef STEAL_BOUND
#define STEAL_BOUND 0
#endif
#ifndef BATCH
#define BATCH 1 /* positions per owner claim (Owner::try_claim_up_to): O3 stores Front := f + k, k <= BATCH */
#endif
#ifndef BROKEN_BATCH_IGNORES_END
#define BROKEN_BATCH_IGNORES_END 0 /* the batch is bounded by the list, not by the End read at O2 */
#endif
#ifndef WAITFREE
#define WAITFREE 0
#endif
#ifndef LIVENESS
#define LIVENESS 0
#endif

#define NT (P + 1) /* threads: workers 0..P-1, the caller P */
#define CALLER P
#define D 2        /* store-buffer depth */

/* Shared memory: one cell per field of every ActivitySlot, plus the frame loop's counters. */
#define FRONT(w) (w)
#define END(w) (P + (w))
#define TRANS(w) (2 * P + (w))
#define LOCK(w) (3 * P + (w))
#define BODY(w) (4 * P + (w))
#define ACTIVE (5 * P)
#define STARTED (5 * P + 1)
#define ARRIVALS (5 * P + 2)
#define DONE (5 * P + 3)
#define NADDR (5 * P + 4)

/* Site labels of core/site.hpp (the stealing protocol's sites). */
mtype = { O1, F1, O2, O3, O4, T1, T2, T3, F2, T4, T5, L1, L2, L3, I1, I2, A1, A2, A3, E1, E2, E3, E4, E5, E6 };

byte mem[NADDR];
byte runs[N];       /* ghost: how often each item ran in the current frame */
byte logm[P];       /* ghost: items each worker processed this frame (its next list) */
byte frames_done;   /* ghost: frames the caller has seen done and checked */

#if TSO
byte ba[NT * D];    /* buffered store addresses, oldest first */
byte bv[NT * D];    /* buffered store values */
byte bn[NT];        /* buffered store count */
/* x86-TSO load: the newest buffered store of this thread to a, else memory. */
#define LV(t, a) ((bn[t] >= 2 && ba[(t) * D + 1] == (a)) -> bv[(t) * D + 1] : \
                  ((bn[t] >= 1 && ba[(t) * D] == (a)) -> bv[(t) * D] : mem[a]))
#define EMPTY(t) (bn[t] == 0)
#else
#define LV(t, a) mem[a]
#define EMPTY(t) true
#endif

#define POP(m) (((m) & 1) + (((m) >> 1) & 1) + (((m) >> 2) & 1) + (((m) >> 3) & 1))

#if WAITFREE
byte solo = 255;    /* the worker running alone, 255: everyone runs */
#define RUNS_NOW(t) (solo >= 254 || solo == (t))
#else
#define RUNS_NOW(t) true
#endif

/* ---------------------------------------------------------------------------------------------------------
 * Printing (guided simulation only: `spin -t` replays a trail and prints these lines; pan prints nothing).
 * ------------------------------------------------------------------------------------------------------- */
inline pr_addr(a) {
  if
  :: a < P -> printf("Front[%d]", a)
  :: a >= P && a < 2 * P -> printf("End[%d]", a - P)
  :: a >= 2 * P && a < 3 * P -> printf("ListTransient[%d]", a - 2 * P)
  :: a >= 3 * P && a < 4 * P -> printf("LockList[%d]", a - 3 * P)
  :: a >= 4 * P && a < 5 * P -> printf("body[%d]", a - 4 * P)
  :: a == ACTIVE -> printf("active")
  :: a == STARTED -> printf("started")
  :: a == ARRIVALS -> printf("arrivals")
  :: a == DONE -> printf("done")
  fi
}
inline pr_thread(t) {
  if
  :: t == CALLER -> printf("caller  ")
  :: else -> printf("worker %d", t)
  fi
}

/* ---------------------------------------------------------------------------------------------------------
 * Accesses. The first argument is the site label.
 * ------------------------------------------------------------------------------------------------------- */
/* plain load (x86 mov, any order) */
inline ld(s, t, a, r) {
  d_step { r = LV(t, a); pr_thread(t); printf("  %e  load  ", s); pr_addr(a); printf(" -> %d\n", r) }
}
/* plain store (x86 mov, any order but seq_cst): buffered under TSO */
inline st(s, t, a, v) {
#if TSO
  d_step {
    bn[t] < D; ba[t * D + bn[t]] = a; bv[t * D + bn[t]] = v; bn[t]++;
    pr_thread(t); printf("  %e  store ", s); pr_addr(a); printf(" := %d   (into the store buffer)\n", v)
  }
#else
  d_step { mem[a] = v; pr_thread(t); printf("  %e  store ", s); pr_addr(a); printf(" := %d\n", v) }
#endif
}
/* store of a labelled site under the policy: SEQCST stores are seq_cst = xchg on x86 */
inline sp(s, t, a, v) {
#if POLICY == SEQCST && TSO
  d_step {
    EMPTY(t); mem[a] = v;
    pr_thread(t); printf("  %e  xchg  ", s); pr_addr(a); printf(" := %d (seq_cst store), buffer drained\n", v)
  }
#else
  st(s, t, a, v)
#endif
}
/* locked exchange: drains the buffer, then reads and writes memory in one step; old value into r */
inline xchg(s, t, a, v, r) {
  d_step {
    EMPTY(t); r = mem[a]; mem[a] = v;
    pr_thread(t); printf("  %e  xchg  ", s); pr_addr(a); printf(" := %d (was %d), buffer drained\n", v, r)
  }
}
/* locked add (lock xadd): drains the buffer; old value into r */
inline rmw(s, t, a, delta, r) {
  d_step {
    EMPTY(t); r = mem[a]; mem[a] = mem[a] + delta;
    pr_thread(t); printf("  %e  rmw   ", s); pr_addr(a); printf(" := %d (was %d)\n", mem[a], r)
  }
}
/* mfence: waits until this thread's buffer is empty */
inline mfence(s, t) {
  d_step { EMPTY(t); pr_thread(t); printf("  %e  mfence\n", s) }
}
/* drains thread j's whole buffer in one step (membarrier's IPI on j's CPU) */
inline drain(j) {
#if TSO
  d_step {
    do
    :: bn[j] > 0 ->
       mem[ba[j * D]] = bv[j * D]; ba[j * D] = ba[j * D + 1]; bv[j * D] = bv[j * D + 1];
       ba[j * D + 1] = 0; bv[j * D + 1] = 0; bn[j]--
    :: else -> break
    od
  }
#else
  skip
#endif
}
/* the StoreLoad fence F1 (owner, s == F1) or F2 (thief, s == F2) under the policy */
inline fence(s, t) {
#if POLICY == PAPER
  skip /* no StoreLoad fence */
#elif POLICY == ASYM
  if
  :: s == F1 -> skip /* compiler barrier only */
  :: else ->
     mfence(s, t); /* membarrier is a syscall: serializes the caller */
     q = 0;
     do
     :: q < NT -> drain(q); q++
     :: else -> break
     od;
     q = 0;
     printf("worker %d  F2  membarrier: every thread's store buffer drained\n", t)
  fi
#else
  mfence(s, t)
#endif
}
/* blocking wait until a load of a satisfies cond (a wait loop whose spinning is not of interest) */
#define AWAIT(s, t, a, cond) d_step { (LV(t, a) cond); pr_thread(t); printf("  %e  await ", s); pr_addr(a); printf(" %d\n", LV(t, a)) }

/* ---------------------------------------------------------------------------------------------------------
 * Lists as bitmasks: helpers (no shared access).
 * ------------------------------------------------------------------------------------------------------- */
/* out := the item at flat position pos of list m (N if none) */
inline nth_item(m, pos, out) {
  out = 0; x = 0;
  do
  :: out >= N -> break
  :: out < N && ((m >> out) & 1) && x == pos -> break
  :: out < N && ((m >> out) & 1) && x != pos -> x++; out++
  :: out < N && !((m >> out) & 1) -> out++
  od;
  x = 0
}
/* out := the items at flat positions [lo, hi) of list m */
inline positions(m, lo, hi, out) {
  out = 0; x = 0; i = 0;
  do
  :: i >= N -> break
  :: i < N && ((m >> i) & 1) ->
     if
     :: x >= lo && x < hi -> out = out | (1 << i)
     :: else
     fi;
     x++; i++
  :: i < N && !((m >> i) & 1) -> i++
  od;
  x = 0; i = 0
}

/* Thief: L1, L2, T1, T2 and the copy of the list body, as one step (see find_work). */
#if STEAL_BOUND
#define BOUND_OK (ns < STEAL_BOUND)
#else
#define BOUND_OK true
#endif
#define CAN_STEAL(t, v) (LV(t, LOCK(v)) == 0 && EMPTY(t) && LV(t, FRONT(v)) < LV(t, END(v)))
inline take_and_plan(t, v) {
  mem[LOCK(v)] = 1;
  fr = mem[FRONT(v)]; tend = mem[END(v)]; vb = mem[BODY(v)];
  mid = fr + (tend - fr) / 2; /* items_left_to_victim = remaining / 2 */
  printf("worker %d  L1 L2  LockList[%d] taken;  T1 load Front[%d] -> %d;  T2 load End[%d] -> %d  (list body %d)\n",
         t, v, v, fr, v, tend, vb);
  fr = 0
}

/* Owner::install: the list `list` into slot w, by thread t, under LockList[w]. One step: lock_spinning (L1/L2
 * until free; a locked xchg drains t's buffer), the body, I1, I2 written to memory, and L3 (buffered under
 * TSO). Writing the protected cells straight to memory is one legal flush schedule, and nobody can tell it
 * from a later one: other threads read Front/End/body of slot w only under LockList[w] (T1, T2), which they
 * cannot take before L3 reaches memory, after the cells before it (FIFO); thread t reads its own values. */
inline install(t, w, list) {
  d_step {
    (EMPTY(t) && mem[LOCK(w)] == 0);
    mem[LOCK(w)] = 1;
    mem[BODY(w)] = list; mem[FRONT(w)] = 0; mem[END(w)] = POP(list);
    pr_thread(t); printf("  L1 L2  LockList[%d] taken;  list body[%d] := %d;  I1 store Front[%d] := 0;  I2 store End[%d] := %d\n",
                         w, w, list, w, w, POP(list));
#if TSO && POLICY != SEQCST
    ba[t * D] = LOCK(w); bv[t * D] = 0; bn[t] = 1;
    pr_thread(t); printf("  L3  store LockList[%d] := 0   (into the store buffer)\n", w)
#else
    mem[LOCK(w)] = 0;
    pr_thread(t); printf("  L3  store LockList[%d] := 0\n", w)
#endif
  }
}

/* ---------------------------------------------------------------------------------------------------------
 * A worker: frame_loop.hpp's await_frame_start, run_frame (drain, A2, find_work) and arrive.
 * ------------------------------------------------------------------------------------------------------- */
proctype Worker(byte me) provided (RUNS_NOW(_pid - 1)) { /* pids: init 0, workers 1..P, caller P+1, flushers */
  byte k = 1;     /* frame */
  byte f;         /* Owner::front_ (private copy of Front[me]) */
  byte e, x, i, j, q, item, v, fr, mid, tend, vb, fa, share, steps, ns;

frame_start:
  f = 0; /* the arriver's install reset Owner::front_ */
  ns = 0;
  AWAIT(E6, me, DONE, >= k - 1);
  AWAIT(E2, me, STARTED, >= k);
  logm[me] = 0;

claim_loop:
  /* Owner::try_claim, until the list is exhausted */
  do
  :: true ->
#if WAITFREE
     if
     :: solo == 255 -> solo = me; steps = 0 /* freeze everyone else from here on */
     :: true
     fi;
#endif
     sp(O1, me, TRANS(me), 1);
#if WAITFREE
     if :: solo == me -> steps++ :: else fi;
     if :: solo == 255 -> solo = me; steps = 0 :: true fi;
#endif
     fence(F1, me);
#if WAITFREE
     if :: solo == me -> steps++ :: else fi;
     if :: solo == 255 -> solo = me; steps = 0 :: true fi;
#endif
     ld(O2, me, END(me), e);
#if WAITFREE
     if :: solo == me -> steps++ :: else fi;
     if :: solo == 255 -> solo = me; steps = 0 :: true fi;
#endif
     if
     :: f >= e -> /* list exhausted */
        sp(O4, me, TRANS(me), 0);
#if WAITFREE
        if :: solo == me -> steps++; assert(steps <= 5); solo = 254 :: else fi;
#endif
        e = 0;
        break
     :: else ->
        /* q := the batch: up to BATCH positions, bounded by the End read at O2 (the list's length instead
         * under the negative control); always 1 when BATCH is 1, the paper's loop */
#if BATCH == 1
        sp(O3, me, FRONT(me), f + 1);
#else
#if BROKEN_BATCH_IGNORES_END
        vb = LV(me, BODY(me));
        q = (POP(vb) - f < BATCH -> POP(vb) - f : BATCH);
        vb = 0;
#else
        q = (e - f < BATCH -> e - f : BATCH);
#endif
        sp(O3, me, FRONT(me), f + q);
#endif
#if WAITFREE
        if :: solo == me -> steps++ :: else fi;
        if :: solo == 255 -> solo = me; steps = 0 :: true fi;
#endif
        /* O4, and the item at position f runs (ghost), in one step */
        d_step {
#if POLICY == SEQCST && TSO
          EMPTY(me); mem[TRANS(me)] = 0;
          printf("worker %d  O4  xchg  ListTransient[%d] := 0 (seq_cst store), buffer drained\n", me, me);
#elif TSO
          bn[me] < D; ba[me * D + bn[me]] = TRANS(me); bv[me * D + bn[me]] = 0; bn[me]++;
          printf("worker %d  O4  store ListTransient[%d] := 0   (into the store buffer)\n", me, me);
#else
          mem[TRANS(me)] = 0;
          printf("worker %d  O4  store ListTransient[%d] := 0\n", me, me);
#endif
#if BATCH == 1
          q = 1;
#endif
          j = 0;
          do
          :: j >= q -> break
          :: j < q ->
             vb = LV(me, BODY(me));
             nth_item(vb, f, item);
             vb = 0;
             assert(item < N);
#if EXACT
             assert(runs[item] == 0); /* exactly-once */
#endif
             if /* saturates: 3 stands for "3 or more" (under PAPER+TSO an item can ping-pong between two
                 * workers, duplicated at every steal, without bound) */
             :: runs[item] < 3 -> runs[item]++
             :: else
             fi;
#if BOUND_RUNS
             assert(runs[item] <= 2);
#endif
             logm[me] = logm[me] | (1 << item);
             printf("worker %d      runs item %d (flat position %d of its list; run %d time(s) this frame)\n",
                    me, item, f, runs[item]);
             f++; j++; item = 0
          od;
          j = 0; q = 0; e = 0
        }
#if WAITFREE
        if :: solo == me -> steps++; assert(steps <= 5); solo = 254 :: else fi;
#endif
     fi
  od;
  rmw(A2, me, ACTIVE, -1, x); /* active -= 1 */
  assert(x > 0);
  x = 0;

  /* find_work. Abstracted: in core an idle worker polls its victims in rounds (try_lock, T1, T2) and reads
   * `active` (A3) after each round. A failed attempt (kLockBusy, kEmpty) writes no shared cell (the lock it
   * takes it gives back; under TSO its L3 sits in the buffer until flushed, which only delays the thread's own
   * next xchg and makes others' L1 see "busy", again no effect), so here an idle worker waits until it can
   * take some victim's free LockList and see Front < End there (T1, T2), or until A3 reads 0. Any victim may
   * be chosen: a superset of core's fixed order. */
find_work:
  do
  :: d_step { /* steal from me+1 */
       (BOUND_OK && CAN_STEAL(me, (me + 1) % P));
       v = (me + 1) % P;
       take_and_plan(me, v)
     } -> break
  :: d_step { /* steal from me+2 (P = 3) */
       (P > 2 && BOUND_OK && CAN_STEAL(me, (me + 2) % P));
       v = (me + 2) % P;
       take_and_plan(me, v)
     } -> break
  :: d_step { /* A3: every worker idle, the frame's work is done */
       (LV(me, ACTIVE) == 0);
       printf("worker %d  A3  load  active -> 0   (frame over)\n", me)
     } -> goto arrive
  od;
  rmw(A1, me, ACTIVE, 1, x);
  x = 0;
  sp(T3, me, END(v), mid);
  fence(F2, me);
#if BROKEN_SKIP_REREAD
  fa = mid; /* Defect::kSkipFrontReread: no T4, no T5 */
#else
T4_wait:
  do
  :: d_step { LV(me, TRANS(v)) == 0;
              printf("worker %d  T4  load  ListTransient[%d] -> 0\n", me, v) } -> break
  :: d_step { LV(me, TRANS(v)) != 0;
              printf("worker %d  T4  load  ListTransient[%d] -> 1   (spins)\n", me, v) }
  od;
  ld(T5, me, FRONT(v), fa);
#endif
  /* L3 (a release: a left mover, so it joins the next step) and keep_unclaimed: [max(mid, fa), tend) */
  d_step {
#if POLICY == SEQCST && TSO
    EMPTY(me); mem[LOCK(v)] = 0;
    printf("worker %d  L3  xchg  LockList[%d] := 0 (seq_cst store), buffer drained\n", me, v);
#elif TSO
    bn[me] < D; ba[me * D + bn[me]] = LOCK(v); bv[me * D + bn[me]] = 0; bn[me]++;
    printf("worker %d  L3  store LockList[%d] := 0   (into the store buffer)\n", me, v);
#else
    mem[LOCK(v)] = 0;
    printf("worker %d  L3  store LockList[%d] := 0\n", me, v);
#endif
    if
    :: fa < mid -> fa = mid
    :: else
    fi;
    positions(vb, fa, tend, share);
    printf("worker %d      keeps items %d (bitmask) of flat positions [%d, %d)\n", me, share, fa, tend);
    fa = 0; mid = 0; tend = 0; vb = 0; v = 0
  };
  if
  :: share == 0 -> /* kSkippedAll */
     rmw(A2, me, ACTIVE, -1, x);
     assert(x > 0);
     x = 0;
     goto find_work
  :: else -> /* kStolen: install the share into our own slot, then drain it */
     install(me, me, share);
     share = 0; f = 0;
#if STEAL_BOUND
     ns++;
#endif
     goto claim_loop
  fi;

arrive:
  rmw(E3, me, ARRIVALS, 1, x);
  if
  :: x + 1 == k * P -> /* last arriver */
     x = 0;
     d_step {
#if !EXACT
       /* remove_duplicates: an id in two logs stays with the lower worker id */
       j = 0; i = 0;
       do
       :: j < P -> logm[j] = logm[j] & ~i; i = i | logm[j]; j++
       :: else -> break
       od;
       j = 0; i = 0
#else
       skip
#endif
     }
     if
     :: k < FRAMES ->
        j = 0;
        do
        :: j < P -> install(me, j, logm[j]); j++
        :: else -> break
        od;
        j = 0
     :: else
     fi;
     sp(E4, me, ACTIVE, P);
     sp(E5, me, DONE, k)
  :: else -> x = 0
  fi;
  k++;
  if
  :: k <= FRAMES -> goto frame_start
  :: else
  fi
}

/* The caller: releases each frame (E1), waits for it (E6) and checks that every item ran (once). */
proctype Caller() provided (RUNS_NOW(CALLER)) {
  byte k = 1, i;
  do
  :: k <= FRAMES ->
     sp(E1, CALLER, STARTED, k);
     AWAIT(E6, CALLER, DONE, >= k);
     d_step {
       i = 0;
       do
       :: i < N ->
#if EXACT
          assert(runs[i] == 1);
#else
          assert(runs[i] >= 1);
#endif
          runs[i] = 0; i++
       :: else -> break
       od;
       i = 0;
       frames_done++;
       printf("caller    frame %d done: every item ran (exactly-once check: %d)\n", k, EXACT)
     };
     k++
  :: else -> break
  od
}

#if TSO
/* The store buffer's drain: the oldest entry of thread t's buffer reaches memory, at any time. */
proctype Flusher(byte t) provided (RUNS_NOW(_pid - P - 2)) {
end_flush:
  do
  :: d_step {
       bn[t] > 0;
       mem[ba[t * D]] = bv[t * D];
       printf("  flush   "); pr_thread(t); printf(": "); pr_addr(ba[t * D]); printf(" := %d reaches memory\n", bv[t * D]);
       ba[t * D] = ba[t * D + 1]; bv[t * D] = bv[t * D + 1];
       ba[t * D + 1] = 0; bv[t * D + 1] = 0; bn[t]--
     }
  od
}
#endif

init {
  byte w, i, lo, hi;
  d_step {
    /* StealingWorkers' constructor: block_allocation, every list installed, active = P */
    w = 0;
    do
    :: w < P ->
       lo = N * w / P; hi = N * (w + 1) / P;
       i = lo;
       do
       :: i < hi -> mem[BODY(w)] = mem[BODY(w)] | (1 << i); i++
       :: else -> break
       od;
       mem[END(w)] = hi - lo;
       w++
    :: else -> break
    od;
    mem[ACTIVE] = P;
    w = 0; i = 0; lo = 0; hi = 0
  };
  atomic {
    w = 0;
    do
    :: w < P -> run Worker(w); w++
    :: else -> break
    od;
    w = 0;
    run Caller();
#if TSO
    do
    :: w < NT -> run Flusher(w); w++
    :: else -> break
    od;
    w = 0
#endif
  }
}

#if LIVENESS
/* Every frame terminates (check with weak fairness: pan -a -f -N term). */
ltl term { <> (frames_done == FRAMES) }
/* A thief waiting at T4 (worker 1 = pid 2) eventually stops waiting: fails without fairness (the paper's
 * starvation: the owner preempted inside a claim), holds with weak fairness. */
ltl starve { [] ((Worker[2]@T4_wait) -> <> !(Worker[2]@T4_wait)) }
#endif
