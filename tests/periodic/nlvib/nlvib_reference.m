% Reference numbers from NLvib (Krack & Gross 2019; github.com/maltekrack/NLvib) for
% geardyn's tests: its example 01 (Duffing, H = 7, N = 29) and example 03 (two-DOF
% oscillator with a unilateral spring, H = 21, N = 1024), continued as the examples do,
% then every crossing of chosen frequencies solved at fixed frequency by Newton on
% NLvib's own residual, and the folds located by maximising the frequency along the
% branch. Our script: it only calls NLvib's functions.
%
%   octave-cli --no-gui nlvib_reference.m /path/to/NLvib OUTDIR
args = argv();
nlvib = args{1};
outdir = args{2};
addpath(fullfile(nlvib, 'SRC'));
addpath(fullfile(nlvib, 'SRC', 'MechanicalSystems'));
addpath(fullfile(nlvib, 'EXAMPLES', '01_Duffing'));
warning('off', 'all');

function [X, ok] = newton_fixed(res, X, Om)
  % Newton on R(X, Om) = 0 at fixed Om; res returns [R, dR/dX] (dR over X only)
  for it = 1:60
    [R, J] = res(X, Om);
    dx = -J \ R;
    X = X + dx;
    if norm(dx) <= 1e-14 * max(1, norm(X)), break; end
  end
  [R, ~] = res(X, Om);
  ok = norm(R) <= 1e-11 * max(1, norm(X));
end

function [R, J] = fd_res(fun, X, Om)
  % residual and central-difference Jacobian of fun([X; Om])
  R = fun([X; Om]);
  J = zeros(length(R), length(X));
  for k = 1:length(X)
    h = 1e-6 * max(1, abs(X(k)));
    e = zeros(size(X)); e(k) = h;
    J(:, k) = (fun([X + e; Om]) - fun([X - e; Om])) / (2 * h);
  end
end

function [R, J] = an_res(fun, X, Om)
  [R, dR] = fun([X; Om]);
  J = dR(:, 1:end-1);
end

function [o, y] = om_fixed(fun, k, c, y0)
  % Newton on [R(y); y_k - c] = 0: the branch's point at coordinate k = c
  y = y0;
  for it = 1:60
    [R, dR] = fun(y);
    G = [R; y(k) - c];
    Jg = [dR; zeros(1, length(y))];
    Jg(end, k) = 1;
    dy = -Jg \ G;
    y = y + dy;
    if norm(dy) <= 1e-15 * max(1, norm(y)), break; end
  end
  o = y(end);
end

function [Om, X] = fold_refine(fun, Xa, Xb, Xc)
  % the extremum of Om along the branch through three points around a fold: the
  % coordinate k that varies most is fixed at c, Om(c) from Newton on [R; X_k - c], and
  % Om(c) extremised by golden section between Xa(k) and Xc(k)
  d = abs(Xc(1:end-1) - Xa(1:end-1));
  [~, k] = max(d);
  sgn = sign(Xb(end) - 0.5 * (Xa(end) + Xc(end)));
  a = Xa(k); c = Xc(k);
  g = (sqrt(5) - 1) / 2;
  x1 = c - g * (c - a); x2 = a + g * (c - a);
  [f1, y1] = om_fixed(fun, k, x1, Xb); [f2, y2] = om_fixed(fun, k, x2, Xb);
  for it = 1:200
    if sgn * f1 > sgn * f2
      c = x2; x2 = x1; f2 = f1; y2 = y1;
      x1 = c - g * (c - a); [f1, y1] = om_fixed(fun, k, x1, y2);
    else
      a = x1; x1 = x2; f1 = f2; y1 = y2;
      x2 = a + g * (c - a); [f2, y2] = om_fixed(fun, k, x2, y1);
    end
    if abs(c - a) < 1e-9 * max(1, abs(c)), break; end
  end
  [Om, X] = om_fixed(fun, k, 0.5 * (a + c), y1);
  X = X(1:end-1);
end

function write_points(file, title, Xb, res, oms, folds)
  % every crossing of each frequency in oms along the branch Xb (columns [X; Om]),
  % in branch order, then the folds
  f = fopen(file, 'w');
  fprintf(f, '# %s\n', title);
  fprintf(f, '# kind crossing Om coefficients (NLvib order: mean, then cos and sin of each harmonic, each over the DOFs)\n');
  Om = Xb(end, :);
  for m = 1:length(oms)
    cr = 0;
    for i = 1:size(Xb, 2) - 1
      if (Om(i) - oms(m)) * (Om(i + 1) - oms(m)) <= 0 && Om(i) ~= Om(i + 1)
        if i > 1 && Om(i) == oms(m), continue; end
        s = (oms(m) - Om(i)) / (Om(i + 1) - Om(i));
        X0 = (1 - s) * Xb(1:end-1, i) + s * Xb(1:end-1, i + 1);
        [X, ok] = newton_fixed(res, X0, oms(m));
        cr = cr + 1;
        if ~ok, fprintf(f, '# crossing %d of %.17g: Newton did not converge\n', cr, oms(m)); continue; end
        fprintf(f, 'point %d %.17g', cr, oms(m)); fprintf(f, ' %.17g', X); fprintf(f, '\n');
      end
    end
  end
  for j = 1:size(folds, 2)
    fprintf(f, 'fold %d %.17g', j, folds(end, j)); fprintf(f, ' %.17g', folds(1:end-1, j)); fprintf(f, '\n');
  end
  fclose(f);
end

function F = find_folds(fun, Xb)
  Om = Xb(end, :);
  F = zeros(size(Xb, 1), 0);
  for i = 2:size(Xb, 2) - 1
    if (Om(i) - Om(i - 1)) * (Om(i + 1) - Om(i)) < 0
      [o, X] = fold_refine(fun, Xb(:, i - 1), Xb(:, i), Xb(:, i + 1));
      F(:, end + 1) = [X; o];
    end
  end
end

function [R, dR] = fd_full(fun, y)
  [R, J] = fd_res(fun, y(1:end-1), y(end));
  h = 1e-6 * max(1, abs(y(end)));
  dR = [J, (fun([y(1:end-1); y(end) + h]) - fun([y(1:end-1); y(end) - h])) / (2 * h)];
end

%% example 01: Duffing (its own residual, no analytic Jacobian)
mu = 1; zeta = 0.05; kappa = 1; gamma = 0.1; P = 0.18;
H = 7; N = 4 * H + 1; Om_s = .5; Om_e = 1.6;
Q = (-Om_s^2 * mu + 1i * Om_s * zeta + kappa) \ P;
x0 = [0; real(Q); -imag(Q); zeros(2 * (H - 1), 1)];
fun1 = @(X) HB_residual_Duffing(X, mu, zeta, kappa, gamma, P, H, N);
% Octave's optimset cannot take @fsolve (NLvib's default): the same options given
solopt = optimset('Display', 'off', 'Jacobian', 'on', 'MaxIter', 50);
X1 = solve_and_continue(x0, fun1, Om_s, Om_e, .01, struct('jac', 'none'), [], ...
  optimset(solopt, 'Jacobian', 'off'));
res1 = @(X, Om) fd_res(fun1, X, Om);
F1 = find_folds(@(y) fd_full(fun1, y), X1);
write_points(fullfile(outdir, 'duffing_ref.txt'), ...
  'NLvib example 01 (Duffing mu 1, zeta 0.05, kappa 1, gamma 0.1, P 0.18), H = 7, N = 29, Om 0.5 -> 1.6', ...
  X1, res1, [0.5 0.8 1.0 1.2 1.4 1.5 1.6], F1);

%% example 03: two-DOF oscillator with a unilateral spring
mi = [1 1]; ki = [0 1 1]; di = .03 * ki; Fex1 = [0; .1];
nl = struct('type', 'unilateralSpring', 'stiffness', 1e2, 'gap', 1, 'force_direction', [1; 0]);
osc = ChainOfOscillators(mi, di, ki, nl, Fex1);
H = 21; N = 2^10; Om_e = .5; Om_s = .8;
Q1 = (-Om_s^2 * osc.M + 1i * Om_s * osc.D + osc.K) \ Fex1;
y0 = zeros((2 * H + 1) * length(Q1), 1);
y0(length(Q1) + (1:2 * length(Q1))) = [real(Q1); -imag(Q1)];
fun3 = @(X) HB_residual(X, osc, H, N, 'FRF');
X3 = solve_and_continue(y0, fun3, Om_s, Om_e, .0085, struct('Dscale', [ones(size(y0)); Om_s]), [], solopt);
res3 = @(X, Om) an_res(fun3, X, Om);
printf('example 03: %d points, Om from %.6f to %.6f, last %.6f\n', size(X3, 2), min(X3(end, :)), max(X3(end, :)), X3(end, end));
save('-ascii', fullfile(outdir, 'ex03_branch.txt'), 'X3');
F3 = find_folds(fun3, X3);
write_points(fullfile(outdir, 'nlvib_ex03_ref.txt'), ...
  'NLvib example 03 (masses 1 1, springs ki [0 1 1], dampers 0.03 ki, unilateral spring 100 gap 1 on DOF 1, force 0.1 on DOF 2), H = 21, N = 1024, Om 0.8 -> 0.5', ...
  X3, res3, [0.8 0.76 0.74 0.7 0.66 0.6 0.55 0.5], F3);
