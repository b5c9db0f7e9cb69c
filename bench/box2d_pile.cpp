// box2d_pile.cpp - the pile of gen_pile.sh in Box2D 2.4 (Debian libbox2d-dev).
// Usage: box2d_pile N CR MU TILL
// N circles of radius 0.05 m and 1 kg (density 1/(pi r^2)) on the lattice
// of gen_pile.sh (W = ceil(sqrt(N)) a row, 0.12 m apart, the first at
// x = 0.11 m, z = 0.1 m, each moved along x by 1e-3 m times the same
// Park-Miller number in (-1, 1), seed 4242), in a box of static edges: the
// floor y = 0 and walls x = 0 and x = W*0.12 + 0.1 m; restitution CR and
// friction MU on every fixture (Box2D mixes restitution by max, friction by
// the geometric mean: both give CR and MU here), gravity -9.80665 m/s^2,
// stepped at 240 Hz with 8 velocity and 3 position iterations (Box2D's
// defaults, its restitution threshold 1 m/s and linear slop 0.005 m) for
// round(TILL*240) steps. Prints one CSV line:
//   N,seconds,worst overlap (m),largest speed (m/s)
// seconds: clock_gettime(CLOCK_MONOTONIC) around the stepping alone; worst
// overlap: the largest penetration, over every pair of balls and every ball
// and wall, at the end (0 if none); largest speed: the largest |v| of a
// ball at the end.
#include <box2d/box2d.h>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <vector>

int main(int argc, char **argv)
{
	if (argc != 5) {
		std::fprintf(stderr, "usage: box2d_pile N CR MU TILL\n");
		return 2;
	}
	const int n = std::atoi(argv[1]);
	const double cr = std::atof(argv[2]), mu = std::atof(argv[3]), till = std::atof(argv[4]);
	const double r = 0.05, g = 9.80665, pi = std::acos(-1.0);
	int w = (int)std::sqrt((double)n);
	if (w * w < n)
		w++;
	const double x1 = w * 0.12 + 0.1, rows = (n + w - 1) / w, h = 0.1 + 0.12 * rows + 1.0;

	b2World world(b2Vec2(0.0f, (float)-g));
	b2BodyDef sd;
	b2Body *box = world.CreateBody(&sd);
	b2Vec2 corners[3][2] = {{b2Vec2(0, 0), b2Vec2((float)x1, 0)},
		{b2Vec2(0, 0), b2Vec2(0, (float)h)}, {b2Vec2((float)x1, 0), b2Vec2((float)x1, (float)h)}};
	for (auto &c : corners) {
		b2EdgeShape e;
		e.SetTwoSided(c[0], c[1]);
		b2FixtureDef fd;
		fd.shape = &e;
		fd.friction = (float)mu;
		fd.restitution = (float)cr;
		box->CreateFixture(&fd);
	}
	std::vector<b2Body *> balls;
	double seed = 4242;
	for (int i = 0; i < n; i++) {
		seed = std::fmod(seed * 16807, 2147483647.0);
		const double u = seed / 2147483647.0;
		b2BodyDef bd;
		bd.type = b2_dynamicBody;
		bd.position.Set((float)(0.11 + 0.12 * (i % w) + 1e-3 * (2 * u - 1)), (float)(0.1 + 0.12 * (i / w)));
		b2Body *b = world.CreateBody(&bd);
		b2CircleShape c;
		c.m_radius = (float)r;
		b2FixtureDef fd;
		fd.shape = &c;
		fd.density = (float)(1.0 / (pi * r * r));
		fd.friction = (float)mu;
		fd.restitution = (float)cr;
		b->CreateFixture(&fd);
		balls.push_back(b);
	}

	const long steps = std::lround(till * 240);
	timespec t0, t1;
	clock_gettime(CLOCK_MONOTONIC, &t0);
	for (long s = 0; s < steps; s++)
		world.Step(1.0f / 240.0f, 8, 3);
	clock_gettime(CLOCK_MONOTONIC, &t1);
	const double secs = (t1.tv_sec - t0.tv_sec) + 1e-9 * (t1.tv_nsec - t0.tv_nsec);

	double over = 0, speed = 0;
	for (int i = 0; i < n; i++) {
		const b2Vec2 p = balls[i]->GetPosition(), v = balls[i]->GetLinearVelocity();
		over = std::fmax(over, r - p.y);
		over = std::fmax(over, r - p.x);
		over = std::fmax(over, r - (x1 - p.x));
		speed = std::fmax(speed, std::hypot((double)v.x, (double)v.y));
		for (int j = i + 1; j < n; j++) {
			const b2Vec2 q = balls[j]->GetPosition();
			over = std::fmax(over, 2 * r - std::hypot((double)p.x - q.x, (double)p.y - q.y));
		}
	}
	std::printf("%d,%.6f,%.3g,%.3g\n", n, secs, over, speed);
	return 0;
}
