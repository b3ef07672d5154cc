program test_sha256
  !! SHA-256 (superjoin_utils_sha256) against the FIPS 180-4 examples: "abc"
  !! (one block), the 448-bit message (two blocks: the padding spills over),
  !! the empty message, a million "a" fed in uneven pieces, array feeding,
  !! and 24 MB of reals (hashed in place, whole and in pieces that split
  !! blocks) against sha256sum of the same bytes written to a file.
  use superjoin_kinds, only: wp, i8
  use superjoin_utils_sha256, only: sha256_t, update, digest, sha256_hex
  use superjoin_testing, only: check, finish, temp_dir
  implicit none (type, external)

  call vectors()
  call pieces()
  call arrays()
  call large()
  call finish()

contains

  subroutine vectors()
    call check(sha256_hex('abc') == 'ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad', &
         'FIPS 180-4: "abc"')
    call check(sha256_hex('abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq') == &
         '248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1', 'FIPS 180-4: the 448-bit message')
    call check(sha256_hex('') == 'e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855', &
         'the empty message')
  end subroutine vectors

  subroutine pieces()
    type(sha256_t) :: s
    integer :: fed, n
    fed = 0
    n = 1
    do while (fed < 1000000)
       n = min(mod(n*7, 131) + 1, 1000000 - fed)
       call update(s, repeat('a', n))
       fed = fed + n
    end do
    call check(digest(s) == 'cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0', &
         'one million "a" in uneven pieces')
  end subroutine pieces

  subroutine arrays()
    type(sha256_t) :: s, t
    real(wp) :: x(3) = [1.0_wp, -2.5_wp, 0.0_wp]
    integer(i8) :: m(2) = [7_i8, -1_i8]
    call update(s, x)
    call update(s, m)
    call update(t, transfer(x, repeat(' ', 24))//transfer(m, repeat(' ', 16)))
    call check(digest(s) == digest(t), 'arrays are fed as their bytes')
    x(3) = -0.0_wp
    call update(s, x)
    call check(digest(s) /= digest(t), 'a different byte gives a different digest')
  end subroutine arrays

  subroutine large()
    integer, parameter :: N = 3*1024*1024 + 5   ! 24 MB and 40 bytes: the last block partial
    real(wp), allocatable :: x(:)
    type(sha256_t) :: whole, parts, text
    character(:), allocatable :: path, bytes
    character(len=64) :: expected
    integer :: i, unit, stat
    allocate (x(N))
    do i = 1, N
       x(i) = sin(real(i, wp))*1.0e3_wp
    end do
    call update(whole, x)
    call update(parts, x(1:1001))          ! 8 bytes left in the buffer
    call update(parts, x(1002:))
    bytes = transfer(x, repeat(' ', 8*N))
    call update(text, bytes(1:13))         ! pieces of odd lengths
    call update(text, bytes(14:100013))
    call update(text, bytes(100014:))
    path = temp_dir()//'/superjoin_test_sha256.bin'
    open (newunit=unit, file=path, access='stream', form='unformatted', status='replace')
    write (unit) x
    close (unit)
    call execute_command_line('sha256sum '//path//' > '//path//'.sum', exitstat=stat)
    call check(stat == 0, 'sha256sum ran')
    expected = ''
    open (newunit=unit, file=path//'.sum', status='old', iostat=stat)
    if (stat == 0) read (unit, '(a64)', iostat=stat) expected
    close (unit)
    call execute_command_line('rm -f '//path//' '//path//'.sum')
    call check(digest(whole) == expected, '24 MB of reals: the digest of sha256sum')
    call check(digest(parts) == expected, '24 MB of reals in two pieces')
    call check(digest(text) == expected, '24 MB as text in pieces of odd lengths')
  end subroutine large
end program test_sha256
