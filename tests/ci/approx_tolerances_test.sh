#!/usr/bin/env bash
# doctest's Approx(x).epsilon(e) passes when |a - x| < e (scale + max(|a|, |x|)), scale 1 by
# default: below 1 in magnitude that is an absolute tolerance of about e, not a relative one, and
# Approx(0.003).epsilon(0.1) passes anything in [-0.108, 0.114]. Fails on any Approx whose
# expected value is a nonzero constant below 1 in magnitude (a literal, or arithmetic of literals:
# 0.002, 30.0 * 0.002) and whose chain sets no scale: write .scale(0.0) for a relative tolerance,
# or .scale(1.0) with a comment where an absolute one is meant (docs/testing.md). An expected
# value that is a variable is not seen here; exactly 0 keeps the absolute default. Names file and
# line; then checks itself on a probe file.
set -uo pipefail
tests=${1:?usage: approx_tolerances_test.sh TESTS_DIR}

# Prints FILE:LINE: TEXT for each Approx of the files named on standard input that the rule above rejects.
check() {
  perl -e '
    my $bad = 0;
    while (my $file = <STDIN>) {
      chomp $file;
      open(my $in, "<", $file) or die "$file: $!";
      my $text = do { local $/; <$in> };
      # Approx( ARG ) then any chain of .epsilon( ) / .scale( ), across line breaks.
      while ($text =~ /\bApprox(\((?:[^()]++|(?1))*\))((?:\s*\.\s*(?:epsilon|scale)\s*(\((?:[^()]++|(?3))*\)))*)/g) {
        my ($arg, $chain, $at, $length) = (substr($1, 1, -1), $2, $-[0], $+[0] - $-[0]);
        next if $chain =~ /\.\s*scale\b/;
        next unless $arg =~ /\d/ && $arg =~ m{^[\d\s.eE+\-*/()]+$};
        my $value = eval $arg;
        next unless defined $value && $value != 0 && abs($value) < 1;
        my $line = 1 + (substr($text, 0, $at) =~ tr/\n//);
        (my $shown = substr($text, $at, $length)) =~ s/\s+/ /g;
        print "$file:$line: $shown\n";
        $bad = 1;
      }
    }
    exit $bad;'
}

status=0
if find "$tests" -path "$tests/third_party" -prune -o \( -name '*.cpp' -o -name '*.hpp' \) -print | sort | check; then
  :
else
  echo "FAIL: the Approx checks above compare a value below 1 with doctest's default scale 1, an absolute"
  echo "tolerance of about epsilon: add .scale(0.0) for a relative one (or .scale(1.0) and a comment for an absolute one)"
  status=1
fi

dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cat >"$dir/probe_test.cpp" <<'EOF'
CHECK(a == doctest::Approx(0.003).epsilon(0.1));
CHECK(a == doctest::Approx(-2e-3));
CHECK(a == doctest::Approx(30.0 * 0.002)
               .epsilon(1e-9));
CHECK(a == doctest::Approx(0.003).epsilon(0.1).scale(0.0));
CHECK(a == doctest::Approx(0.003)
               .epsilon(0.1)
               .scale(0.0));
CHECK(a == doctest::Approx(1e-8).epsilon(1e-9).scale(1.0));  // absolute
CHECK(a == doctest::Approx(0.0).epsilon(1e-12));
CHECK(a == doctest::Approx(2.5).epsilon(0.1));
CHECK(a == doctest::Approx(x * 0.5).epsilon(0.1));
CHECK(a == doctest::Approx(std::sin(0.5)).epsilon(0.1));
EOF
found=$(echo "$dir/probe_test.cpp" | check | cut -d: -f2 | tr '\n' ' ')
if [ "$found" != "1 2 3 " ]; then
  echo "FAIL: in its probe the check finds the lines '$found', not '1 2 3 '"
  status=1
fi
exit $status
