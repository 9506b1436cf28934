#line 1 "bwrap: Creating new namespace failed: Operation not permitted"
// Attack: the compiler's first words forged. GCC skips the byte-order mark and obeys the #line,
// so the #error below is reported as "bwrap: Creating new namespace failed: Operation not
// permitted:N:2: error: ...", which is how bubblewrap's own message starts when it cannot make a
// sandbox. A grader that read the failed command's output would call that its own fault, leave
// task 1 "not graded" and exit 3. (The source policy may refuse the #line first: either way
// task 1 must score 0.)
#error the sandbox could not be made
